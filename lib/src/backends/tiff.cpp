// The libtiff backend (backends.hpp): a TIFF's layout, its GeoTIFF tags, and the samples of the
// plain single-channel rasters DEMs are, read as OpenImageIO's TIFF reader reads them (both decode
// through libtiff). The GeoKey directory is read here as libgeotiff 1.7 reads it (GTIFNew,
// GTIFKeyGetSHORT), since libgeotiff itself would load PROJ's whole dependency tree.
#include "backends.hpp"

#include <tiffio.h>

#include <algorithm>
#include <cstring>
#include <iterator>
#include <map>
#include <mutex>

namespace tinlod::backends {

namespace {

// GeoTIFF 1.0's tags (§2.4, §2.6).
constexpr ttag_t k_pixel_scale = 33550, k_intergraph_matrix = 33920, k_tie_points = 33922,
                 k_matrix = 34264, k_key_directory = 34735, k_double_params = 34736,
                 k_ascii_params = 34737;
// GeoKeys tinlod reads (§6.2).
constexpr std::uint16_t k_model_type_key = 1024, k_raster_type_key = 1025,
                        k_geographic_type_key = 2048, k_projected_type_key = 3072;

// Registered with libtiff as libgeotiff's XTIFFOpen registers them, so that they read with the
// same types and counts (a 16-bit count before the values).
char k_name_scale[] = "GeoPixelScale", k_name_intergraph[] = "Intergraph TransformationMatrix",
     k_name_matrix[] = "GeoTransformationMatrix", k_name_ties[] = "GeoTiePoints",
     k_name_keys[] = "GeoKeyDirectory", k_name_doubles[] = "GeoDoubleParams",
     k_name_ascii[] = "GeoASCIIParams";
const TIFFFieldInfo k_geotiff_fields[] = {
    {k_pixel_scale, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, true, true, k_name_scale},
    {k_intergraph_matrix, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, true, true, k_name_intergraph},
    {k_matrix, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, true, true, k_name_matrix},
    {k_tie_points, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, true, true, k_name_ties},
    {k_key_directory, -1, -1, TIFF_SHORT, FIELD_CUSTOM, true, true, k_name_keys},
    {k_double_params, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, true, true, k_name_doubles},
    {k_ascii_params, -1, -1, TIFF_ASCII, FIELD_CUSTOM, true, false, k_name_ascii}};

TIFFExtendProc g_parent_extender = nullptr;

void add_geotiff_fields(TIFF *tif) {
    TIFFMergeFieldInfo(tif, k_geotiff_fields, std::size(k_geotiff_fields));
    if (g_parent_extender)
        g_parent_extender(tif);
}

// Errors and warnings of one file stay with it: counted, never printed, and never sent to the
// process's handlers (which OpenImageIO sets for its own TIFF reader).
int count_message(TIFF *, void *count, const char *, const char *, va_list) {
    ++*static_cast<int *>(count);
    return 1;
}
int drop_message(TIFF *, void *, const char *, const char *, va_list) { return 1; }

std::vector<double> doubles(TIFF *tif, ttag_t tag) {
    std::uint16_t count = 0;
    double *values = nullptr;
    if (!TIFFGetField(tif, tag, &count, &values) || !values)
        return {};
    return std::vector<double>(values, values + count);
}

// The SHORT GeoKeys of the key directory, read as libgeotiff 1.7 reads them: a directory that
// GTIFNew refuses (a newer version, too many keys, a key pointing past its values or into a tag
// it does not know) has no keys at all. libgeotiff returns a SHORT key stored among the
// directory's own values (rather than in its entry) wrongly; this reads the value the file holds.
std::map<std::uint16_t, std::uint16_t> short_geokeys(TIFF *tif) {
    // libgeotiff's limits (geo_keyp.h): values in a tag, and the directory it keeps.
    constexpr int k_max_values = 1000, k_directory_shorts = 4 + k_max_values;
    std::uint16_t n = 0;
    std::uint16_t *raw = nullptr;
    if (!TIFFGetField(tif, k_key_directory, &n, &raw) || !raw)
        return {};
    // libgeotiff reads past the tag's values as zeros (its copy has room for more).
    const auto at = [&](int i) -> int { return i < n ? raw[i] : 0; };
    if (at(0) > 1) // KeyDirectoryVersion
        return {};
    const int keys = at(3);
    if (keys * 8 >= k_directory_shorts * 2)
        return {};
    std::uint16_t n_doubles = 0;
    double *unused = nullptr;
    if (TIFFGetField(tif, k_double_params, &n_doubles, &unused) && n_doubles > k_max_values)
        return {};
    // The ASCII values' length, their final NUL left out.
    char *ascii = nullptr;
    const bool has_ascii = TIFFGetField(tif, k_ascii_params, &ascii) && ascii;
    int ascii_length = has_ascii ? std::uint16_t(std::strlen(ascii) + 1) : 0;
    if (has_ascii && ascii_length > 0 && ascii[ascii_length - 1] == '\0')
        --ascii_length;
    std::map<std::uint16_t, std::uint16_t> shorts;
    for (int k = 1; k <= keys; ++k) {
        const int key = at(4 * k), location = at(4 * k + 1), count = at(4 * k + 2),
                  offset = at(4 * k + 3);
        switch (location) {
        case 0: // the value in the entry itself
            if (count != 1)
                return {};
            shorts[std::uint16_t(key)] = std::uint16_t(offset);
            break;
        case k_key_directory:
            if (n < offset + count)
                return {};
            if (count > 0)
                shorts[std::uint16_t(key)] = std::uint16_t(at(offset));
            else
                shorts.erase(std::uint16_t(key));
            break;
        case k_double_params:
            if (n_doubles < offset + count)
                return {};
            shorts.erase(std::uint16_t(key));
            break;
        case k_ascii_params:
            if (!has_ascii)
                return {};
            if (!(offset + count == ascii_length + 1 && count > 0) &&
                !(offset < ascii_length && offset + count > ascii_length) &&
                offset + count > ascii_length)
                return {};
            shorts.erase(std::uint16_t(key));
            break;
        default:
            return {};
        }
    }
    return shorts;
}

std::optional<std::uint16_t> find(const std::map<std::uint16_t, std::uint16_t> &keys,
                                  std::uint16_t key) {
    const auto it = keys.find(key);
    return it == keys.end() ? std::nullopt : std::optional<std::uint16_t>(it->second);
}

// The samples of a plain raster: one channel, no extra samples, of a type OpenImageIO reads as it
// is stored, through a compression it leaves to libtiff. Valid while its TiffFile lives.
class TiffRaster final : public RasterFile {
  public:
    TiffRaster(TIFF *tif, const RasterSpec &spec, std::size_t sample_bytes, int &errors)
        : tif_(tif), spec_(spec), bytes_(sample_bytes), errors_(errors) {}
    const RasterSpec &spec() const override { return spec_; }

    bool read(SampleType type, void *out) override {
        if (type != spec_.type)
            return false;
        const int before = errors_;
        const bool ok = TIFFIsTiled(tif_) ? read_tiles(static_cast<unsigned char *>(out))
                                          : read_strips(static_cast<unsigned char *>(out));
        return ok && errors_ == before;
    }

    // Rows [y0, y1): the strips or rows of tiles that hold them, the last one kept (the next
    // window often falls in it).
    bool read_window(int y0, int y1, SampleType type, void *out) override {
        if (type != spec_.type)
            return false;
        const int before = errors_;
        std::uint32_t block = 0;
        if (TIFFIsTiled(tif_))
            TIFFGetField(tif_, TIFFTAG_TILELENGTH, &block);
        else
            TIFFGetFieldDefaulted(tif_, TIFFTAG_ROWSPERSTRIP, &block);
        block = std::clamp<std::uint32_t>(block, 1, std::uint32_t(spec_.height));
        const std::size_t row_bytes = std::size_t(spec_.width) * bytes_;
        for (std::uint32_t b = std::uint32_t(y0) / block * block; b < std::uint32_t(y1);
             b += block) {
            const std::uint32_t rows = std::min(block, std::uint32_t(spec_.height) - b);
            if (b != block_from_) {
                block_from_ = std::uint32_t(-1);
                block_.resize(rows * row_bytes);
                const bool ok = TIFFIsTiled(tif_) ? read_tiles(block_.data(), b, b + rows)
                                                  : read_strips(block_.data(), b, b + rows);
                if (!ok || errors_ != before)
                    return false;
                block_from_ = b;
            }
            const std::uint32_t lo = std::max(b, std::uint32_t(y0));
            const std::uint32_t hi = std::min(b + rows, std::uint32_t(y1));
            std::memcpy(static_cast<unsigned char *>(out) + (lo - std::uint32_t(y0)) * row_bytes,
                        block_.data() + (lo - b) * row_bytes, (hi - lo) * row_bytes);
        }
        return true;
    }

  private:
    // Rows [y0, y1) (whole strips) into `out`.
    bool read_strips(unsigned char *out, std::uint32_t y0 = 0, std::uint32_t y1 = 0) {
        std::uint32_t rows_per_strip = 0;
        TIFFGetFieldDefaulted(tif_, TIFFTAG_ROWSPERSTRIP, &rows_per_strip);
        const std::uint32_t h = y1 > 0 ? y1 : std::uint32_t(spec_.height);
        rows_per_strip = std::clamp<std::uint32_t>(rows_per_strip, 1, std::uint32_t(spec_.height));
        const std::size_t row_bytes = std::size_t(spec_.width) * bytes_;
        for (std::uint32_t row = y0; row < h; row += rows_per_strip) {
            const std::uint32_t rows = std::min(rows_per_strip, h - row);
            const tmsize_t want = tmsize_t(rows * row_bytes);
            const tstrip_t strip = TIFFComputeStrip(tif_, row, 0);
            if (TIFFReadEncodedStrip(tif_, strip, out + (row - y0) * row_bytes, want) != want)
                return false;
        }
        return true;
    }

    // Rows [y0, y1) (whole rows of tiles) into `out`.
    bool read_tiles(unsigned char *out, std::uint32_t y0 = 0, std::uint32_t y1 = 0) {
        std::uint32_t tw = 0, th = 0;
        TIFFGetField(tif_, TIFFTAG_TILEWIDTH, &tw);
        TIFFGetField(tif_, TIFFTAG_TILELENGTH, &th);
        const tmsize_t tile_bytes = TIFFTileSize(tif_);
        if (tw == 0 || th == 0 || tile_bytes != tmsize_t(std::size_t(tw) * th * bytes_))
            return false;
        std::vector<unsigned char> tile(static_cast<std::size_t>(tile_bytes));
        const std::uint32_t w = std::uint32_t(spec_.width);
        const std::uint32_t h = y1 > 0 ? y1 : std::uint32_t(spec_.height);
        for (std::uint32_t y = y0; y < h; y += th)
            for (std::uint32_t x = 0; x < w; x += tw) {
                if (TIFFReadEncodedTile(tif_, TIFFComputeTile(tif_, x, y, 0, 0), tile.data(),
                                        tile_bytes) != tile_bytes)
                    return false;
                const std::size_t cols = std::min(tw, w - x) * bytes_;
                for (std::uint32_t r = 0; r < th && y + r < h; ++r)
                    std::memcpy(out + ((std::size_t(y - y0) + r) * w + x) * bytes_,
                                tile.data() + std::size_t(r) * tw * bytes_, cols);
            }
        return true;
    }

    TIFF *tif_;
    RasterSpec spec_;
    std::size_t bytes_; // of a sample
    int &errors_;
    std::vector<unsigned char> block_; // the strip or row of tiles read last, from block_from_
    std::uint32_t block_from_ = std::uint32_t(-1);
};

class OpenTiff final : public TiffFile {
  public:
    explicit OpenTiff(TIFF *tif, std::unique_ptr<int> errors)
        : tif_(tif), errors_(std::move(errors)) {}
    ~OpenTiff() override { TIFFClose(tif_); }
    OpenTiff(const OpenTiff &) = delete;
    OpenTiff &operator=(const OpenTiff &) = delete;

    std::optional<TiffLayout> layout() override {
        TiffLayout l;
        if (!TIFFGetField(tif_, TIFFTAG_IMAGEWIDTH, &l.width) ||
            !TIFFGetField(tif_, TIFFTAG_IMAGELENGTH, &l.height))
            return std::nullopt;
        TIFFGetFieldDefaulted(tif_, TIFFTAG_SAMPLESPERPIXEL, &l.samples_per_pixel);
        TIFFGetFieldDefaulted(tif_, TIFFTAG_BITSPERSAMPLE, &l.bits_per_sample);
        l.tiled = TIFFGetField(tif_, TIFFTAG_TILEWIDTH, &l.tile_width) &&
                  TIFFGetField(tif_, TIFFTAG_TILELENGTH, &l.tile_height);
        return l;
    }

    GeoTags geo_tags() override {
        GeoTags t;
        const auto keys = short_geokeys(tif_);
        t.model = find(keys, k_model_type_key);
        t.raster = find(keys, k_raster_type_key);
        t.geographic_type = find(keys, k_geographic_type_key);
        t.projected_type = find(keys, k_projected_type_key);
        t.pixel_scale = doubles(tif_, k_pixel_scale);
        t.tie_points = doubles(tif_, k_tie_points);
        t.matrix = doubles(tif_, k_matrix);
        // libtiff knows GDAL_NODATA as an ASCII tag passed with a 16-bit count.
        std::uint16_t count = 0;
        char *text = nullptr;
        if (TIFFGetField(tif_, TIFFTAG_GDAL_NODATA, &count, &text) && text && count > 0)
            t.nodata = std::string(text, strnlen(text, count));
        return t;
    }

    std::unique_ptr<RasterFile> raster() override {
        const std::optional<TiffLayout> l = layout();
        if (!l || *errors_ > 0)
            return nullptr;
        std::uint16_t photometric = PHOTOMETRIC_MINISBLACK, format = SAMPLEFORMAT_UINT;
        std::uint16_t compression = COMPRESSION_NONE, extra = 0, *extra_kinds = nullptr;
        std::uint32_t depth = 1;
        TIFFGetField(tif_, TIFFTAG_PHOTOMETRIC, &photometric);
        TIFFGetFieldDefaulted(tif_, TIFFTAG_SAMPLEFORMAT, &format);
        TIFFGetFieldDefaulted(tif_, TIFFTAG_COMPRESSION, &compression);
        TIFFGetFieldDefaulted(tif_, TIFFTAG_IMAGEDEPTH, &depth);
        TIFFGetField(tif_, TIFFTAG_EXTRASAMPLES, &extra, &extra_kinds);
        // Compressions libtiff decodes alone; OpenImageIO reads JPEG through libtiff's RGBA
        // interface instead.
        static constexpr std::uint16_t k_plain[] = {
            COMPRESSION_NONE,     COMPRESSION_LZW,  COMPRESSION_ADOBE_DEFLATE, COMPRESSION_DEFLATE,
            COMPRESSION_PACKBITS, COMPRESSION_ZSTD, COMPRESSION_LZMA,          COMPRESSION_LERC};
        const bool plain_compression =
            std::find(std::begin(k_plain), std::end(k_plain), compression) != std::end(k_plain) &&
            TIFFIsCODECConfigured(compression);
        if (l->samples_per_pixel != 1 || extra != 0 || depth != 1 ||
            photometric != PHOTOMETRIC_MINISBLACK || !plain_compression)
            return nullptr;
        RasterSpec s;
        s.width = int(l->width);
        s.height = int(l->height);
        s.channels = 1;
        const std::uint16_t bits = l->bits_per_sample;
        if (bits == 8 && format == SAMPLEFORMAT_UINT)
            s.type = SampleType::uint8, s.type_name = "uint8";
        else if (bits == 8 && format == SAMPLEFORMAT_INT)
            s.type = SampleType::int8, s.type_name = "int8";
        else if (bits == 16 && format == SAMPLEFORMAT_UINT)
            s.type = SampleType::uint16, s.type_name = "uint16";
        else if (bits == 16 && format == SAMPLEFORMAT_INT)
            s.type = SampleType::int16, s.type_name = "int16";
        else if (bits == 32 && format == SAMPLEFORMAT_UINT)
            s.type = SampleType::uint32, s.type_name = "uint";
        else if (bits == 32 && format == SAMPLEFORMAT_INT)
            s.type = SampleType::int32, s.type_name = "int";
        else if (bits == 32 && format == SAMPLEFORMAT_IEEEFP)
            s.type = SampleType::float32, s.type_name = "float";
        else if (bits == 64 && format == SAMPLEFORMAT_IEEEFP)
            s.type = SampleType::float64, s.type_name = "double";
        else
            return nullptr;
        s.type_bytes = bits / 8;
        if (s.width <= 0 || s.height <= 0)
            return nullptr;
        return std::make_unique<TiffRaster>(tif_, s, bits / 8, *errors_);
    }

  private:
    TIFF *tif_;
    std::unique_ptr<int> errors_; // libtiff's errors on this file so far
};

class Tiff final : public TiffFiles {
  public:
    std::unique_ptr<TiffFile> open(const std::string &path, bool mapped) override {
        static std::once_flag once;
        std::call_once(once, [] { g_parent_extender = TIFFSetTagExtender(add_geotiff_fields); });
        auto errors = std::make_unique<int>(0);
        const std::unique_ptr<TIFFOpenOptions, void (*)(TIFFOpenOptions *)> options(
            TIFFOpenOptionsAlloc(), TIFFOpenOptionsFree);
        TIFFOpenOptionsSetErrorHandlerExtR(options.get(), count_message, errors.get());
        TIFFOpenOptionsSetWarningHandlerExtR(options.get(), drop_message, nullptr);
        TIFF *tif = TIFFOpenExt(path.c_str(), mapped ? "r" : "rm", options.get());
        if (!tif)
            return nullptr;
        return std::make_unique<OpenTiff>(tif, std::move(errors));
    }
};

} // namespace

extern "C" TiffFiles *tinlod_tiff_backend() {
    static Tiff backend;
    return &backend;
}

} // namespace tinlod::backends
