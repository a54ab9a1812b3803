// Elevation rasters in: SRTM .hgt (our reader); PNG and plain GeoTIFF through libpng and libtiff
// as OpenImageIO would read them, everything else through OpenImageIO (src/backends/); GeoTIFF
// georeferencing from its tags, and geographic-to-metric conversion as PROJ computes it (crs.hpp).
#include "tinlod/raster.hpp"
#include "backends/backends.hpp"
#include "crs.hpp"
#include "tinlod/error.hpp"

#include <glm/glm.hpp>

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <type_traits>

namespace tinlod {

namespace fs = std::filesystem;

namespace {

// What a file says about where it stands on Earth.
struct Georef {
    bool present = false;
    bool geographic = false;    // degrees of longitude/latitude
    int epsg = 0;               // EPSG code of the CRS (geographic or projected), 0 if unknown
    double west = 0, north = 0; // CRS coordinates of the NW corner of the NW pixel's area
    double sx = 1, sy = 1;      // pixel size in CRS units (positive)
    bool flip_columns = false;  // the file's columns run west, its rows north: mirror them
    bool flip_rows = false;
    std::optional<double> nodata;
};

// Samples as read, row 0 = north, with the voids marked.
struct RawGrid {
    int width = 0, height = 0;
    std::vector<float> z;
    std::vector<std::uint8_t> is_void;
};

// Reserves room for `n` values in `v` and has the kernel map all of it at once, in huge pages
// where it can. Touched a 4 KiB page at a time, a raster's arrays cost a page fault each, and a
// fault costs microseconds on a virtual machine: faults were two thirds of `tinlod info` on an SRTM
// tile (docs/decisions/020-startup.md). Where the kernel offers neither, nothing changes.
template <typename T> void reserve_mapped(std::vector<T> &v, std::size_t n) {
    v.reserve(n);
    const std::uintptr_t page = std::uintptr_t(sysconf(_SC_PAGESIZE));
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(v.data());
    const std::uintptr_t lo = (begin + page - 1) / page * page;
    const std::uintptr_t hi = (begin + n * sizeof(T)) / page * page;
    if (hi <= lo)
        return;
    madvise(reinterpret_cast<void *>(lo), hi - lo, MADV_HUGEPAGE);
    madvise(reinterpret_cast<void *>(lo), hi - lo, MADV_POPULATE_WRITE);
}

std::string lower_extension(const std::string &path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext;
}

// Bytes the loader holds per sample of a raster of `channels` samples of `sample_bytes` each, at
// most (docs/decisions/memory-per-sample.md): the samples as read, the float grid, the void mask,
// the fill's marks and indices, the heightfield's heights and mask. A bound: the fills keep
// their state per void, and the heightfield takes over the grid's arrays.
double load_bytes_per_sample(int channels, int sample_bytes) {
    return double(channels) * sample_bytes + 4.0 + 1.0 + 2.0 + 4.0 + 4.0 + 1.0;
}

// Refuses, before any allocation, a w x h raster whose run would need more memory than
// options.max_memory_mb or, by default, this machine has: a header can declare any size.
// `buffer`: a decoder's own scratch (one TIFF tile), bytes, which `layout` describes.
void check_memory(const std::string &path, const LoadOptions &options, std::int64_t w,
                  std::int64_t h, int channels, int sample_bytes, double buffer = 0,
                  const std::string &layout = "") {
    const double per_sample =
        std::max(load_bytes_per_sample(channels, sample_bytes), options.bytes_per_sample);
    const double need = double(w) * double(h) * per_sample + buffer;
    const double mib = 1 << 20;
    const double have = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    const double limit = options.max_memory_mb > 0 ? options.max_memory_mb * mib : have;
    if (!(limit > 0) || need <= limit)
        return;
    std::error_code ec;
    const auto bytes = fs::file_size(path, ec);
    throw Error(path, "a " + std::to_string(w) + "x" + std::to_string(h) + " raster" + layout +
                          " (" + std::to_string(ec ? 0 : bytes) + " bytes on disk) needs about " +
                          std::to_string(std::int64_t(std::ceil(need / mib))) + " MiB, more than " +
                          (options.max_memory_mb > 0 ? "the limit of " : "this machine's ") +
                          std::to_string(std::int64_t(limit / mib)) +
                          " MiB (--max-memory-mb sets the limit)");
}

// Checks a TIFF's declared size and tile size before a reader allocates for it (OpenImageIO
// allocates a tile's buffer when it opens the file).
void check_tiff_memory(const std::string &path, const LoadOptions &options,
                       const backends::TiffLayout &l) {
    const int sample_bytes = std::max(1, (l.bits_per_sample + 7) / 8);
    if (l.tiled)
        check_memory(
            path, options, l.width, l.height, l.samples_per_pixel, sample_bytes,
            double(l.tile_width) * double(l.tile_height) * l.samples_per_pixel * sample_bytes,
            " in tiles of " + std::to_string(l.tile_width) + "x" + std::to_string(l.tile_height));
    else
        check_memory(path, options, l.width, l.height, l.samples_per_pixel, sample_bytes);
}

void check_size(const std::string &path, std::int64_t w, std::int64_t h) {
    if (w < 2 || h < 2)
        throw Error(path, "raster is " + std::to_string(w) + "x" + std::to_string(h) +
                              "; at least 2x2 samples are needed");
    if (w * h > k_max_raster_samples || w > (1 << 20) || h > (1 << 20))
        throw Error(path, "raster is " + std::to_string(w) + "x" + std::to_string(h) +
                              ", beyond the supported maximum of 2^31 samples");
}

// --- SRTM .hgt: big-endian int16, square 1201 or 3601, row 0 north, file name = SW corner. ---

// The side of an SRTM tile (1201 or 3601) and its georeferencing, from its size and name.
int hgt_georef(const std::string &path, const LoadOptions &options, Georef &geo) {
    const auto bytes = fs::file_size(path);
    int n = 0;
    for (int side : {1201, 3601})
        if (bytes == std::uintmax_t(side) * side * 2)
            n = side;
    if (n == 0)
        throw Error(path, "size " + std::to_string(bytes) +
                              " bytes is not an SRTM tile (1201x1201 or 3601x3601 int16 = " +
                              std::to_string(1201 * 1201 * 2) + " or " +
                              std::to_string(3601 * 3601 * 2) + " bytes)");
    // SRTM names the tile by its south-west corner: [NS]dd[EW]ddd, e.g. N42E001.
    const std::string stem = fs::path(path).filename().string();
    auto digits = [&](std::size_t from, std::size_t count) {
        for (std::size_t i = from; i < from + count; ++i)
            if (i >= stem.size() || !std::isdigit(static_cast<unsigned char>(stem[i])))
                return false;
        return true;
    };
    const char ns = stem.empty() ? 0 : char(std::toupper(static_cast<unsigned char>(stem[0])));
    const char ew = stem.size() < 4 ? 0 : char(std::toupper(static_cast<unsigned char>(stem[3])));
    if ((ns == 'N' || ns == 'S') && (ew == 'E' || ew == 'W') && digits(1, 2) && digits(4, 3)) {
        const double lat = std::stod(stem.substr(1, 2)) * (ns == 'S' ? -1 : 1);
        const double lon = std::stod(stem.substr(4, 3)) * (ew == 'W' ? -1 : 1);
        geo.present = true;
        geo.geographic = true;
        geo.epsg = 4326;
        geo.sx = geo.sy = 1.0 / (n - 1);
        // Samples sit on whole-degree lines (pixel is point): the NW sample is at (lon, lat + 1).
        geo.west = lon - geo.sx / 2;
        geo.north = lat + 1 + geo.sy / 2;
    } else if (!options.cell) {
        throw Error(path, "not an SRTM tile name ([NS]dd[EW]ddd.hgt, the south-west corner), so "
                          "where it lies and its spacing are unknown: rename it, or give --cell");
    }
    geo.nodata = -32768.0;
    return n;
}

// `count` heights of an .hgt into `out`, from sample `first` on (file order), a block at a time:
// the file's bytes are never held whole beside the heights.
void read_hgt_samples(const std::string &path, std::size_t first, std::size_t count, float *out) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(std::streamoff(2 * first));
    std::vector<unsigned char> block(std::size_t(1) << 16);
    for (std::size_t done = 0; done < count;) {
        const std::size_t n = std::min(count - done, block.size() / 2);
        if (!in.read(reinterpret_cast<char *>(block.data()), std::streamsize(2 * n)))
            throw Error(path, "cannot read file");
        for (std::size_t i = 0; i < n; ++i)
            out[done + i] = static_cast<std::int16_t>((block[2 * i] << 8) | block[2 * i + 1]);
        done += n;
    }
}

RawGrid read_hgt(const std::string &path, const LoadOptions &options, Georef &geo) {
    const int n = hgt_georef(path, options, geo);
    check_memory(path, options, n, n, 1, 2);
    const std::size_t samples = std::size_t(n) * n;
    RawGrid g;
    g.width = g.height = n;
    reserve_mapped(g.z, samples);
    g.z.resize(samples);
    read_hgt_samples(path, 0, samples, g.z.data());
    return g;
}

// --- GeoTIFF georeferencing, from the tags as stored. ---

// GeoKey values (GeoTIFF 1.0, §6.3).
constexpr std::uint16_t k_model_projected = 1, k_model_geographic = 2;
constexpr std::uint16_t k_raster_pixel_is_area = 1, k_raster_pixel_is_point = 2;
constexpr std::uint16_t k_user_defined = 32767;

// A width x height GeoTIFF's georeferencing. Grids whose columns run west or rows run north (a
// negative pixel scale) are marked to be mirrored into the usual order.
Georef read_geotiff_tags(const std::string &path, int width, int height,
                         const backends::GeoTags &tags) {
    Georef geo;
    const std::uint16_t raster = tags.raster.value_or(k_raster_pixel_is_area);
    const std::uint16_t model = tags.model.value_or(0);
    if (model == k_model_geographic) {
        geo.geographic = true;
        geo.epsg = tags.geographic_type && *tags.geographic_type != k_user_defined
                       ? *tags.geographic_type
                       : 4326;
    } else if (model == k_model_projected && tags.projected_type &&
               *tags.projected_type != k_user_defined) {
        geo.epsg = *tags.projected_type;
    }
    // Pixel corner (i, j) (column i, row j down the file) stands at
    // x = x0 + i * sx, y = y0 - j * sy; a tie point of a pixel-is-point raster names a centre.
    const double centre = raster == k_raster_pixel_is_point ? 0.5 : 0.0;
    const std::vector<double> &scale = tags.pixel_scale, &ties = tags.tie_points,
                              &matrix = tags.matrix;
    double sx = 0, sy = 0, x0 = 0, y0 = 0;
    if (scale.size() >= 2) {
        if (ties.size() >= 6) {
            sx = scale[0];
            sy = scale[1];
            x0 = ties[3] - (ties[0] + centre) * sx;
            y0 = ties[4] + (ties[1] + centre) * sy;
            geo.present = true;
        }
    } else if (matrix.size() >= 16) {
        // The model transformation, x = m0 col + m1 row + m3 and y = m4 col + m5 row + m7: without
        // rotation it is what a tie point and a pixel scale say; a rotation needs a resampling.
        if (matrix[1] != 0.0 || matrix[4] != 0.0)
            throw Error(path, "georeferenced by a rotated or sheared model transformation; "
                              "resample it north up first (gdalwarp)");
        sx = matrix[0];
        sy = -matrix[5];
        x0 = matrix[3] - centre * sx;
        y0 = matrix[7] + centre * sy;
        geo.present = true;
    } else if (ties.size() > 6) {
        throw Error(path, "georeferenced by " + std::to_string(ties.size() / 6) +
                              " ground control points without a pixel scale; resample it to a "
                              "grid first (gdalwarp)");
    }
    if (geo.present) {
        if (sx == 0 || sy == 0)
            throw Error(path, "georeferencing has a pixel size of zero");
        geo.flip_columns = sx < 0;
        geo.flip_rows = sy < 0;
        geo.sx = std::abs(sx);
        geo.sy = std::abs(sy);
        geo.west = sx > 0 ? x0 : x0 + width * sx;
        geo.north = sy > 0 ? y0 : y0 - height * sy;
    }
    if (tags.nodata) {
        std::string text = *tags.nodata;
        const auto first = text.find_first_not_of(" \t\r\n");
        text = first == std::string::npos
                   ? ""
                   : text.substr(first, text.find_last_not_of(" \t\r\n") + 1 - first);
        char *end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size())
            throw Error(path, "GDAL_NODATA is '" + text.substr(0, 40) +
                                  "', not a number: which samples are voids is unknown");
        geo.nodata = v;
    }
    return geo;
}

// Mirrors a w x h grid's columns and/or rows.
template <typename T> void mirror(std::vector<T> &v, int w, int h, bool columns, bool rows) {
    const auto row = [&](int r) { return v.begin() + std::ptrdiff_t(r) * w; };
    if (columns)
        for (int r = 0; r < h; ++r)
            std::reverse(row(r), row(r + 1));
    if (rows)
        for (int r = 0, s = h - 1; r < s; ++r, --s)
            std::swap_ranges(row(r), row(r + 1), row(s));
}

// Mirrors a grid whose georeferencing runs its columns west or its rows north, so that column 0
// is the west edge and row 0 the north edge, as in most files.
void orient(RawGrid &g, const Georef &geo) {
    mirror(g.z, g.width, g.height, geo.flip_columns, geo.flip_rows);
    if (!g.is_void.empty())
        mirror(g.is_void, g.width, g.height, geo.flip_columns, geo.flip_rows);
}

// --- Every other raster: samples in their native type. ---

// Channel `height` of each pixel is its height; where the alpha channel (if any) is 0 the pixel
// is a void. Alpha is read unassociated: a partly transparent pixel keeps its height.
template <typename T>
void copy_heights(const std::vector<T> &src, int channels, int height, int alpha, RawGrid &g) {
    for (std::size_t i = 0; i < g.z.size(); ++i) {
        g.z[i] = static_cast<float>(src[i * channels + height]);
        if (alpha >= 0 && src[i * channels + alpha] == T(0))
            g.is_void[i] = 1;
    }
}

// Why an image with `colours` channels besides alpha is no DEM: a palette or colour image, and
// an 8-bit RGB one most likely Terrain-RGB.
std::string not_a_dem(const std::string &path, const backends::RasterSpec &spec, int colours) {
    char header[26] = {};
    std::ifstream(path, std::ios::binary).read(header, sizeof header);
    // OpenImageIO expands a palette to RGB: the PNG header (colour type, byte 25) tells.
    if (std::memcmp(header, "\x89PNG\r\n\x1a\n", 8) == 0 && header[25] == 3)
        return "a palette image is not a DEM (one channel of heights, and optionally alpha)";
    std::string why = "a colour image (" + std::to_string(colours) + " colour channels of " +
                      spec.type_name + ") is not a DEM (one channel of heights, and " +
                      "optionally alpha)";
    if (colours == 3 && spec.type == backends::SampleType::uint8)
        why += "; it looks like Mapbox Terrain-RGB: use --terrain-rgb";
    return why;
}

template <typename T> constexpr backends::SampleType sample_type_of() {
    using backends::SampleType;
    if constexpr (std::is_same_v<T, std::uint8_t>)
        return SampleType::uint8;
    else if constexpr (std::is_same_v<T, std::int8_t>)
        return SampleType::int8;
    else if constexpr (std::is_same_v<T, std::uint16_t>)
        return SampleType::uint16;
    else if constexpr (std::is_same_v<T, std::int16_t>)
        return SampleType::int16;
    else if constexpr (std::is_same_v<T, std::uint32_t>)
        return SampleType::uint32;
    else if constexpr (std::is_same_v<T, std::int32_t>)
        return SampleType::int32;
    else if constexpr (std::is_same_v<T, double>)
        return SampleType::float64;
    else
        return SampleType::float32;
}

// Calls f(T{}) with T the C++ type of samples of type `t` (float for half and float).
template <typename F> void with_sample_type(backends::SampleType t, F &&f) {
    using backends::SampleType;
    switch (t) {
    case SampleType::int16:
        f(std::int16_t{});
        break;
    case SampleType::uint16:
        f(std::uint16_t{});
        break;
    case SampleType::int32:
        f(std::int32_t{});
        break;
    case SampleType::uint32:
        f(std::uint32_t{});
        break;
    case SampleType::uint8:
        f(std::uint8_t{});
        break;
    case SampleType::int8:
        f(std::int8_t{});
        break;
    case SampleType::float64:
        f(double{});
        break;
    default:
        f(float{});
        break;
    }
}

// The heights (and voids, where alpha is 0) of `file`; nullopt when its reader declines it after
// all.
std::optional<RawGrid> read_samples(const std::string &path, const LoadOptions &options,
                                    backends::RasterFile &file) {
    using backends::SampleType;
    const backends::RasterSpec &spec = file.spec();
    check_size(path, spec.width, spec.height);
    check_memory(path, options, spec.width, spec.height, spec.channels, spec.type_bytes);
    if (spec.depth > 1)
        throw Error(path, "volume images are not elevation rasters");
    const int nc = spec.channels;
    const int alpha = spec.alpha >= 0 && spec.alpha < nc ? spec.alpha : -1;
    const int colours = nc - (alpha >= 0);
    if (options.terrain_rgb && (colours != 3 || spec.type != SampleType::uint8))
        throw Error(path, "--terrain-rgb needs an 8-bit RGB image, this one has " +
                              std::to_string(nc) + " channel(s) of " + spec.type_name);
    if (!options.terrain_rgb && colours != 1)
        throw Error(path, not_a_dem(path, spec, colours));
    RawGrid g;
    g.width = spec.width;
    g.height = spec.height;
    const std::size_t n = std::size_t(g.width) * g.height;
    reserve_mapped(g.z, n);
    g.z.resize(n);
    reserve_mapped(g.is_void, n);
    g.is_void.assign(n, 0);
    bool declined = false;
    auto read = [&](auto tag) {
        using T = decltype(tag);
        std::vector<T> buf;
        reserve_mapped(buf, n * nc);
        buf.resize(n * nc);
        declined = !file.read(sample_type_of<T>(), buf.data());
        return buf;
    };
    const int height = alpha == 0 ? 1 : 0;
    if (options.terrain_rgb) {
        const auto buf = read(std::uint8_t{});
        if (declined)
            return std::nullopt;
        int rgb[3], k = 0;
        for (int c = 0; c < nc; ++c)
            if (c != alpha)
                rgb[k++] = c;
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint8_t *px = &buf[i * nc];
            g.z[i] = static_cast<float>(
                (px[rgb[0]] * 65536.0 + px[rgb[1]] * 256.0 + px[rgb[2]]) / 10.0 - 10000.0);
            if (alpha >= 0 && px[alpha] == 0)
                g.is_void[i] = 1;
        }
        return g;
    }
    const auto heights = [&](auto tag) {
        const auto buf = read(tag);
        if (!declined)
            copy_heights(buf, nc, height, alpha, g);
    };
    with_sample_type(spec.type, heights);
    if (declined)
        return std::nullopt;
    return g;
}

// A raster of any format but .hgt, with its GeoTIFF georeferencing (if a TIFF): PNG and plain
// TIFF through the faster readers, everything else, and what they decline, through OpenImageIO.
RawGrid read_raster(const std::string &path, const std::string &ext, const LoadOptions &options,
                    Georef &geo) {
    std::unique_ptr<backends::TiffFile> tiff;
    std::unique_ptr<backends::RasterFile> fast;
    if (ext == ".tif" || ext == ".tiff") {
        tiff = backends::tiff_files().open(path);
        if (tiff) {
            if (const auto layout = tiff->layout())
                check_tiff_memory(path, options, *layout);
            fast = tiff->raster();
        }
    } else if (ext == ".png") {
        fast = backends::png_files().open_raster(path);
    }
    std::optional<RawGrid> g;
    if (fast)
        g = read_samples(path, options, *fast);
    if (!g) {
        const auto file = backends::image_files().open_raster(path);
        g = read_samples(path, options, *file);
    }
    if (tiff)
        geo = read_geotiff_tags(path, g->width, g->height, tiff->geo_tags());
    return std::move(*g);
}

// Marks voids (the nodata value; NaN only when NaN is the declared nodata) beside those the
// reader marked (alpha 0), and rejects non-finite heights elsewhere.
void mark_voids(const std::string &path, RawGrid &g, const Georef &geo) {
    reserve_mapped(g.is_void, g.z.size());
    g.is_void.resize(g.z.size(), 0);
    const std::size_t n = g.z.size();
    const float *z = g.z.data();
    std::uint8_t *is_void = g.is_void.data();
    // The common case, in one pass without branches: finite heights, the nodata value marked. A
    // nodata value below -1e30 also marks every height below -1e30 (as a double): those at or
    // below the float `low`. NaN for either matches nothing.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const bool has_nodata = geo.nodata && !std::isnan(*geo.nodata);
    const float nodata = has_nodata ? static_cast<float>(*geo.nodata) : nan;
    float low = nan;
    if (has_nodata && *geo.nodata < -1e30) {
        low = static_cast<float>(-1e30);
        if (!(double(low) < -1e30))
            low = std::nextafter(low, -HUGE_VALF);
    }
    std::uint8_t unusual = 0; // a non-finite height that is no void
    for (std::size_t i = 0; i < n; ++i) {
        const float v = z[i];
        const std::uint8_t match = (v == nodata) | (v <= low);
        const std::uint8_t finite = std::fabs(v) <= std::numeric_limits<float>::max();
        unusual |=
            std::uint8_t(is_void[i] == 0) & std::uint8_t(match == 0) & std::uint8_t(finite == 0);
        is_void[i] |= match;
    }
    if (!unusual)
        return;
    // NaN and infinities, one at a time, in order: the first names its place.
    const bool nan_is_nodata = geo.nodata && std::isnan(*geo.nodata);
    for (std::size_t i = 0; i < n; ++i) {
        const float v = z[i];
        if (is_void[i]) {
            continue;
        } else if (std::isnan(v)) {
            if (!nan_is_nodata)
                throw Error(path, "sample at row " + std::to_string(i / g.width) + ", column " +
                                      std::to_string(i % g.width) +
                                      " is NaN (no nodata value declared)");
            is_void[i] = 1;
        } else if (!std::isfinite(v)) {
            throw Error(path, "sample at row " + std::to_string(i / g.width) + ", column " +
                                  std::to_string(i % g.width) + " is infinite");
        }
    }
}

// Numbers the voids of a grid in sample order, so that the fills keep their state per void, not
// per sample: a bit per sample and a count per 64 find a void's number.
class VoidNumbers {
  public:
    explicit VoidNumbers(const std::vector<std::uint8_t> &is_void)
        : bits_((is_void.size() + 63) / 64), before_(bits_.size() + 1, 0) {
        for (std::size_t i = 0; i < is_void.size(); ++i)
            if (is_void[i])
                bits_[i >> 6] |= std::uint64_t{1} << (i & 63);
        for (std::size_t k = 0; k < bits_.size(); ++k)
            before_[k + 1] = before_[k] + std::uint32_t(std::popcount(bits_[k]));
    }
    std::size_t count() const { return before_.back(); }
    // The number of sample i, a void: how many voids come before it.
    std::size_t operator()(std::size_t i) const {
        const std::uint64_t below = bits_[i >> 6] & ((std::uint64_t{1} << (i & 63)) - 1);
        return before_[i >> 6] + std::size_t(std::popcount(below));
    }
    // visit(i) for each void sample i, in order.
    template <typename Visit> void each(Visit &&visit) const {
        for (std::size_t k = 0; k < bits_.size(); ++k)
            for (std::uint64_t b = bits_[k]; b != 0; b &= b - 1)
                visit(k * 64 + std::size_t(std::countr_zero(b)));
    }

  private:
    std::vector<std::uint64_t> bits_;
    std::vector<std::uint32_t> before_; // voids before each block of 64 samples
};

// First guess of the voids: ring by ring inward, each the average of its known 8 neighbours.
void ring_fill(RawGrid &g, const VoidNumbers &voids) {
    // Ring k holds the voids k steps (8-way) from the valid samples; each ring is found from the
    // last, so the fill is linear in the voids (rescanning every void each ring took minutes for a
    // half-void SRTM1 tile). A void is known once filled in an earlier ring.
    const int w = g.width, h = g.height;
    constexpr std::uint8_t k_known = 1, k_queued = 2;
    std::vector<std::uint8_t> state(voids.count(), 0);
    const auto known = [&](std::size_t i) {
        return !g.is_void[i] || (state[voids(i)] & k_known) != 0;
    };
    // Queues void i unless it is known or queued already.
    const auto queue = [&](std::size_t i, std::vector<std::size_t> &to) {
        std::uint8_t &s = state[voids(i)];
        if (s == 0) {
            s = k_queued;
            to.push_back(i);
        }
    };
    auto neighbours = [&](std::size_t i, auto &&visit) {
        const int r = int(i / w), c = int(i % w);
        for (int dr = -1; dr <= 1; ++dr)
            for (int dc = -1; dc <= 1; ++dc) {
                const int rr = r + dr, cc = c + dc;
                if ((dr || dc) && rr >= 0 && rr < h && cc >= 0 && cc < w)
                    visit(std::size_t(rr) * w + cc);
            }
    };
    std::vector<std::size_t> ring, next;
    voids.each([&](std::size_t i) {
        neighbours(i, [&](std::size_t n) {
            if (known(n))
                queue(i, ring);
        });
    });
    std::vector<float> value;
    while (!ring.empty()) {
        value.assign(ring.size(), 0.0f);
        for (std::size_t k = 0; k < ring.size(); ++k) {
            double sum = 0;
            int count = 0;
            neighbours(ring[k], [&](std::size_t n) {
                if (known(n)) {
                    sum += g.z[n];
                    ++count;
                }
            });
            value[k] = float(sum / count);
        }
        next.clear();
        for (std::size_t k = 0; k < ring.size(); ++k) {
            g.z[ring[k]] = value[k];
            state[voids(ring[k])] = k_known;
        }
        for (std::size_t i : ring)
            neighbours(i, [&](std::size_t n) {
                if (!known(n))
                    queue(n, next);
            });
        ring.swap(next);
    }
}

void harmonic_fill(RawGrid &g, const VoidNumbers &voids);

// Regions of fewer voids are solved directly at their own resolution.
constexpr std::size_t k_coarse_min_voids = 4096;

// Samples in the bounding box of `cells` (indices into a grid of width w).
std::size_t box_area(const std::vector<std::size_t> &cells, int w) {
    std::size_t c0 = SIZE_MAX, c1 = 0, r0 = SIZE_MAX, r1 = 0;
    for (const std::size_t i : cells) {
        c0 = std::min(c0, i % std::size_t(w)), c1 = std::max(c1, i % std::size_t(w));
        r0 = std::min(r0, i / std::size_t(w)), r1 = std::max(r1, i / std::size_t(w));
    }
    return (c1 - c0 + 1) * (r1 - r0 + 1);
}

// A first guess for a large region of voids: the same fill on a grid of half the resolution over
// the region's bounding box, interpolated back (cascadic multigrid). Conjugate gradients then
// only remove what the coarse grid cannot show, instead of carrying the boundary's heights
// across the whole region a step per iteration.
void coarse_guess(RawGrid &g, const std::vector<std::size_t> &cells) {
    const int w = g.width;
    int c0 = w, c1 = -1, r0 = g.height, r1 = -1;
    for (const std::size_t i : cells) {
        const int r = int(i / std::size_t(w)), c = int(i % std::size_t(w));
        c0 = std::min(c0, c), c1 = std::max(c1, c), r0 = std::min(r0, r), r1 = std::max(r1, r);
    }
    c0 = std::max(0, c0 - 1), r0 = std::max(0, r0 - 1);
    c1 = std::min(w - 1, c1 + 1), r1 = std::min(g.height - 1, r1 + 1);
    RawGrid coarse;
    coarse.width = (c1 - c0 + 2) / 2;
    coarse.height = (r1 - r0 + 2) / 2;
    if (coarse.width < 2 || coarse.height < 2)
        return; // a strip: the ring fill is guess enough
    const std::size_t n = std::size_t(coarse.width) * coarse.height;
    coarse.z.assign(n, 0.0f);
    coarse.is_void.assign(n, 1);
    std::vector<std::uint8_t> count(n, 0);
    // Each coarse sample is the mean of the valid samples of its 2 x 2 block.
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) {
            const std::size_t i = std::size_t(r) * w + c;
            const std::size_t k = std::size_t((r - r0) / 2) * coarse.width + (c - c0) / 2;
            if (!g.is_void[i])
                coarse.z[k] += g.z[i], ++count[k];
        }
    for (std::size_t k = 0; k < n; ++k)
        if (count[k])
            coarse.z[k] /= float(count[k]), coarse.is_void[k] = 0;
    const VoidNumbers coarse_voids(coarse.is_void);
    ring_fill(coarse, coarse_voids);
    harmonic_fill(coarse, coarse_voids);
    // Bilinear interpolation: block k's centre is at fine column c0 + 2k + 0.5.
    const auto at = [&](int x, int y) { return coarse.z[std::size_t(y) * coarse.width + x]; };
    for (const std::size_t i : cells) {
        const double x =
            std::clamp((double(i % std::size_t(w)) - c0 - 0.5) / 2, 0.0, double(coarse.width - 1));
        const double y =
            std::clamp((double(i / std::size_t(w)) - r0 - 0.5) / 2, 0.0, double(coarse.height - 1));
        const int x0 = std::min(int(x), coarse.width - 2), y0 = std::min(int(y), coarse.height - 2);
        const double fx = x - x0, fy = y - y0;
        g.z[i] = float((1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
                       fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1)));
    }
}

// Fills each 4-connected region of voids with the harmonic (Laplace) interpolation of the valid
// samples around it: every filled value the mean of its 4 neighbours (those inside the grid),
// the smoothest surface through the region's boundary, with no terraces. Solved by conjugate
// gradients (Jacobi-preconditioned) from the ring fill, one region at a time, so the work follows
// the voids and a small hole is not iterated as long as a large one.
void harmonic_fill(RawGrid &g, const VoidNumbers &voids) {
    const int w = g.width, h = g.height;
    std::vector<std::int32_t> index(voids.count(), -1); // of each void in its region
    const auto index_of = [&](std::size_t i) -> std::int32_t & { return index[voids(i)]; };
    std::vector<std::size_t> cells;
    std::vector<std::array<std::int32_t, 4>> links;
    std::vector<double> u, b, diag, r, zr, p, q;
    // Visits the 4 neighbours inside the grid: (direction 0..3, index).
    const auto neighbours = [&](std::size_t i, auto &&visit) {
        const int row = int(i / std::size_t(w)), col = int(i % std::size_t(w));
        if (row > 0)
            visit(0, i - w);
        if (row + 1 < h)
            visit(1, i + w);
        if (col > 0)
            visit(2, i - 1);
        if (col + 1 < w)
            visit(3, i + 1);
    };
    voids.each([&](std::size_t seed) {
        if (index_of(seed) >= 0)
            return;
        // The region: breadth first from the seed over void 4-neighbours.
        cells.assign(1, seed);
        index_of(seed) = 0;
        for (std::size_t k = 0; k < cells.size(); ++k)
            neighbours(cells[k], [&](int, std::size_t n) {
                if (g.is_void[n] && index_of(n) < 0) {
                    index_of(n) = std::int32_t(cells.size());
                    cells.push_back(n);
                }
            });
        // Large regions start from a coarser solution; thin ones (whose box is mostly valid)
        // converge fast anyway and would make the coarse grid cost more than the voids.
        const std::size_t m = cells.size();
        if (m >= k_coarse_min_voids && 4 * m >= box_area(cells, w))
            coarse_guess(g, cells);
        // Row k of the system: deg * u_k - (void neighbours) = (valid neighbours' heights).
        links.assign(m, {-1, -1, -1, -1});
        u.resize(m), b.assign(m, 0.0), diag.assign(m, 0.0);
        double scale = 1;
        for (std::size_t k = 0; k < m; ++k) {
            u[k] = g.z[cells[k]];
            neighbours(cells[k], [&](int d, std::size_t n) {
                diag[k] += 1;
                if (g.is_void[n]) {
                    links[k][std::size_t(d)] = index_of(n);
                } else {
                    b[k] += g.z[n];
                    scale = std::max(scale, double(std::abs(g.z[n])));
                }
            });
        }
        const auto apply = [&](const std::vector<double> &x, std::vector<double> &out) {
            for (std::size_t k = 0; k < m; ++k) {
                double v = diag[k] * x[k];
                for (const std::int32_t l : links[k])
                    if (l >= 0)
                        v -= x[std::size_t(l)];
                out[k] = v;
            }
        };
        // Done when every value is within a millionth of the heights' scale of its neighbours'
        // mean (3 mm for 3000 m): a few roundings of the float it is stored in.
        const double tolerance = 1e-6 * scale;
        const auto converged = [&] {
            for (std::size_t k = 0; k < m; ++k)
                if (std::abs(r[k]) > tolerance * diag[k])
                    return false;
            return true;
        };
        r.resize(m), zr.resize(m), p.resize(m), q.resize(m);
        apply(u, q);
        for (std::size_t k = 0; k < m; ++k) {
            r[k] = b[k] - q[k];
            zr[k] = r[k] / diag[k];
            p[k] = zr[k];
        }
        double rz = 0;
        for (std::size_t k = 0; k < m; ++k)
            rz += r[k] * zr[k];
        // Conjugate gradients end in at most m steps in exact arithmetic; the cap only guards
        // against rounding.
        for (std::size_t step = 0; step < 2 * m + 100 && !converged(); ++step) {
            apply(p, q);
            double pq = 0;
            for (std::size_t k = 0; k < m; ++k)
                pq += p[k] * q[k];
            if (!(pq > 0))
                break; // the residual is already at rounding level
            const double alpha = rz / pq;
            double rz_next = 0;
            for (std::size_t k = 0; k < m; ++k) {
                u[k] += alpha * p[k];
                r[k] -= alpha * q[k];
                zr[k] = r[k] / diag[k];
                rz_next += r[k] * zr[k];
            }
            const double beta = rz_next / rz;
            rz = rz_next;
            for (std::size_t k = 0; k < m; ++k)
                p[k] = zr[k] + beta * p[k];
        }
        for (std::size_t k = 0; k < m; ++k)
            g.z[cells[k]] = float(u[k]);
    });
}

// Voids are missing data, never heights. Whole rows/columns of voids at the edges are cropped
// away (too large to invent); the rest are filled smoothly from the valid samples around them.
void crop_and_fill(const std::string &path, RawGrid &g, Georef &geo, Heightfield &hf, bool fill) {
    // The box of the valid samples, a row at a time (most rows start and end valid).
    int top = g.height, bottom = -1, left = g.width, right = -1;
    std::int64_t voids = 0;
    for (int r = 0; r < g.height; ++r) {
        const std::uint8_t *row = g.is_void.data() + std::size_t(r) * g.width;
        const std::uint8_t *first = std::find(row, row + g.width, 0);
        if (first == row + g.width) {
            voids += g.width;
            continue;
        }
        int last = g.width - 1;
        while (row[last])
            --last;
        voids += std::count(row, row + g.width, 1);
        top = std::min(top, r), bottom = r;
        left = std::min(left, int(first - row)), right = std::max(right, last);
    }
    if (bottom < 0)
        throw Error(path, "every sample is a void (nodata); there is no terrain to use");
    hf.voids = voids;
    if (top > 0 || left > 0 || bottom < g.height - 1 || right < g.width - 1) {
        const int w = right - left + 1, h = bottom - top + 1;
        check_size(path, w, h);
        RawGrid cropped;
        cropped.width = w;
        cropped.height = h;
        cropped.z.resize(std::size_t(w) * h);
        cropped.is_void.resize(std::size_t(w) * h);
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) {
                const std::size_t src = std::size_t(r + top) * g.width + c + left;
                cropped.z[std::size_t(r) * w + c] = g.z[src];
                cropped.is_void[std::size_t(r) * w + c] = g.is_void[src];
            }
        hf.cropped = std::int64_t(g.width) * g.height - std::int64_t(w) * h;
        geo.west += left * geo.sx;
        geo.north -= top * geo.sy;
        g = std::move(cropped);
    }
    const VoidNumbers remaining(g.is_void);
    if (remaining.count() == 0)
        return;
    if (!fill)
        throw Error(path, std::to_string(remaining.count()) + " void samples inside the terrain");
    ring_fill(g, remaining);
    harmonic_fill(g, remaining);
    hf.filled = std::int64_t(remaining.count());
}

// Local metric frame: projected CRSs keep their units; geographic ones go to the UTM zone of
// the centre (crs.hpp); ground spacing is measured there at the centre of the raster.
void apply_georef(const std::string &path, const Georef &geo, const LoadOptions &options,
                  const RawGrid &g, Heightfield &hf) {
    if (!geo.present) {
        hf.dx = hf.dy = options.cell.value_or(1.0);
        hf.crs = "none (cell " + std::to_string(hf.dx) + ")";
        return;
    }
    if (options.cell)
        throw Error(path, "georeferenced, so its ground spacing comes from the file: --cell "
                          "applies only to rasters without georeferencing");
    if (!std::isfinite(geo.sx) || !std::isfinite(geo.sy) || !std::isfinite(geo.west) ||
        !std::isfinite(geo.north))
        throw Error(path, "georeferencing is not finite (pixel scale or tie point)");
    // Centre of the SW sample in CRS units.
    const double sw_x = geo.west + geo.sx / 2;
    const double sw_y = geo.north - (g.height - 0.5) * geo.sy;
    hf.native_epsg = geo.epsg ? geo.epsg : geo.geographic ? 4326 : 0;
    hf.native_geographic = geo.geographic;
    hf.native_x0 = sw_x;
    hf.native_y0 = sw_y;
    hf.native_dx = geo.sx;
    hf.native_dy = geo.sy;
    if (!geo.geographic) {
        hf.dx = geo.sx;
        hf.dy = geo.sy;
        hf.origin_x = sw_x;
        hf.origin_y = sw_y;
        if (geo.epsg)
            crs::check(path, geo.epsg, false);
        hf.crs = geo.epsg ? "EPSG:" + std::to_string(geo.epsg) : "projected (unknown EPSG)";
        return;
    }
    const int epsg = geo.epsg ? geo.epsg : 4326;
    crs::check(path, epsg, true);
    const double lon_c = sw_x + (g.width - 1) * geo.sx / 2;
    const double lat_c = sw_y + (g.height - 1) * geo.sy / 2;
    if (!(std::abs(lat_c) <= 84))
        throw Error(path, "latitude beyond UTM coverage (|lat| > 84)");
    // Longitudes run -180..180, or 0..360 in some files; beyond, the UTM zone is meaningless.
    if (!(lon_c >= -180 && lon_c <= 360))
        throw Error(path, "georeferencing puts the centre at longitude " + std::to_string(lon_c) +
                              ", not on Earth");
    const int zone = std::clamp(int(std::floor((lon_c + 180) / 6)) + 1, 1, 60);
    const int utm = (lat_c >= 0 ? 32600 : 32700) + zone;
    const auto p =
        crs::Transformation(path, epsg, utm)
            .apply(std::vector<glm::dvec2>{
                {lon_c, lat_c}, {lon_c + geo.sx, lat_c}, {lon_c, lat_c + geo.sy}, {sw_x, sw_y}});
    hf.dx = glm::length(p[1] - p[0]);
    hf.dy = glm::length(p[2] - p[0]);
    const glm::dvec2 sw = p[3];
    if (!std::isfinite(hf.dx) || !std::isfinite(hf.dy) || hf.dx <= 0 || hf.dy <= 0)
        throw Error(path, "georeferencing gives no usable ground spacing");
    hf.origin_x = sw.x;
    hf.origin_y = sw.y;
    hf.crs = "EPSG:" + std::to_string(utm) + " (UTM zone " + std::to_string(zone) +
             (lat_c >= 0 ? "N" : "S") + ", from EPSG:" + std::to_string(epsg) + " degrees)";
}

} // namespace

namespace {

// What every loader checks first: the file and the options.
void check_input(const std::string &path, const LoadOptions &options) {
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw Error(path, "no such file");
    if (!fs::is_regular_file(path, ec))
        throw Error(path, "not a regular file");
    if (fs::file_size(path, ec) == 0)
        throw Error(path, "file is empty");
    if (options.cell && (!(*options.cell > 0) || !std::isfinite(*options.cell)))
        throw Error("--cell", "ground size of a pixel must be a positive number");
    if (!std::isfinite(options.zscale) || options.zscale == 0)
        throw Error("--zscale", "must be a non-zero finite number");
    {
        std::ifstream probe(path);
        if (!probe)
            throw Error(path, "cannot open for reading");
    }
}

Heightfield load(const std::string &path, const LoadOptions &options) {
    check_input(path, options);
    Georef geo;
    RawGrid g;
    const std::string ext = lower_extension(path);
    if (ext == ".hgt") {
        g = read_hgt(path, options, geo);
    } else {
        g = read_raster(path, ext, options, geo);
    }
    orient(g, geo);
    mark_voids(path, g, geo);
    Heightfield hf;
    crop_and_fill(path, g, geo, hf, options.fill_voids);
    apply_georef(path, geo, options, g, hf);
    hf.width = g.width;
    hf.height = g.height;
    // Files run north to south; the Heightfield runs south to north.
    mirror(g.z, g.width, g.height, false, true);
    hf.z = std::move(g.z);
    if (options.zscale != 1.0)
        for (float &z : hf.z)
            z = static_cast<float>(z * options.zscale);
    if (hf.voids > 0) {
        mirror(g.is_void, g.width, g.height, false, true);
        hf.void_mask = std::move(g.is_void);
    }
    return hf;
}

} // namespace

Heightfield load_heightfield(const std::string &path, const LoadOptions &options) {
    try {
        return load(path, options);
    } catch (const std::bad_alloc &) {
        // What the estimate did not foresee (a decoder's own buffers) still names the file.
        throw Error(path, "out of memory while loading it");
    }
}

// --- DEMs read by windows (raster.hpp: DemWindows). ---

struct DemWindows::Impl {
    std::string path;
    LoadOptions options;
    Heightfield grid;
    Georef geo;
    int file_width = 0, file_height = 0;        // before the crop
    int left = 0, top = 0;                      // the crop's first column and row (north row 0)
    std::unique_ptr<backends::TiffFile> tiff;   // a TIFF's, which its plain reader needs
    std::unique_ptr<backends::RasterFile> file; // libtiff's for a plain TIFF, else OpenImageIO's
    int channels = 1, alpha = -1;
    backends::SampleType type = backends::SampleType::int16;
    bool hgt = false;
    mutable std::mutex lock; // a reader reads one window at a time
    // The strip filled last (its number, its rows): a band's rows and the next band's often fall
    // in one strip.
    mutable std::mutex fill_lock;
    mutable int filled_strip = -1;
    mutable std::vector<float> filled_rows;

    // Rows [a, b) of the file as load() orients them (north row 0, west column 0), every column,
    // the voids marked.
    RawGrid oriented(int a, int b) const {
        RawGrid g;
        g.width = file_width, g.height = b - a;
        const std::size_t n = std::size_t(g.width) * std::size_t(g.height);
        g.z.resize(n);
        g.is_void.assign(n, 0);
        // The file's own rows: mirrored when its rows run north.
        const int fa = geo.flip_rows ? file_height - b : a,
                  fb = geo.flip_rows ? file_height - a : b;
        const std::lock_guard<std::mutex> guard(lock);
        if (hgt) {
            read_hgt_samples(path, std::size_t(fa) * std::size_t(file_width), n, g.z.data());
        } else {
            const int height = alpha == 0 ? 1 : 0;
            const auto heights = [&](auto tag) {
                using T = decltype(tag);
                std::vector<T> buf(n * std::size_t(channels));
                if (!file->read_window(fa, fb, sample_type_of<T>(), buf.data()))
                    throw Error(path, "cannot read rows " + std::to_string(fa) + " to " +
                                          std::to_string(fb - 1) + " (truncated or corrupt)");
                copy_heights(buf, channels, height, alpha, g);
            };
            with_sample_type(type, heights);
        }
        mirror(g.z, g.width, g.height, geo.flip_columns, geo.flip_rows);
        mirror(g.is_void, g.width, g.height, geo.flip_columns, geo.flip_rows);
        mark_voids(path, g, geo);
        return g;
    }

    // Rows [a, b) of the cropped grid (north row 0), voids marked, not filled.
    RawGrid cropped(int a, int b) const {
        RawGrid g = oriented(a + top, b + top);
        if (left == 0 && grid.width == file_width)
            return g;
        RawGrid c;
        c.width = grid.width, c.height = g.height;
        for (int r = 0; r < g.height; ++r) {
            const std::size_t from = std::size_t(r) * std::size_t(g.width) + std::size_t(left);
            c.z.insert(c.z.end(), g.z.begin() + std::ptrdiff_t(from),
                       g.z.begin() + std::ptrdiff_t(from) + c.width);
            c.is_void.insert(c.is_void.end(), g.is_void.begin() + std::ptrdiff_t(from),
                             g.is_void.begin() + std::ptrdiff_t(from) + c.width);
        }
        return c;
    }
};

DemWindows::DemWindows(const std::string &path, const LoadOptions &options)
    : impl_(std::make_unique<Impl>()) {
    Impl &m = *impl_;
    check_input(path, options);
    if (options.terrain_rgb)
        throw Error(path, "a Terrain-RGB raster is read whole: give more memory");
    m.path = path;
    m.options = options;
    const std::string ext = lower_extension(path);
    if (ext == ".hgt") {
        m.hgt = true;
        m.file_width = m.file_height = hgt_georef(path, options, m.geo);
    } else {
        // A plain TIFF through libtiff (as load_heightfield reads it), the rest through
        // OpenImageIO, whose plugins' libraries alone take about 90 MiB.
        if (ext == ".tif" || ext == ".tiff")
            m.tiff = backends::tiff_files().open(path, false);
        if (m.tiff)
            m.file = m.tiff->raster();
        if (!m.file)
            m.file = backends::image_files().open_raster(path);
        const backends::RasterSpec &spec = m.file->spec();
        check_size(path, spec.width, spec.height);
        if (spec.depth > 1)
            throw Error(path, "volume images are not elevation rasters");
        m.channels = spec.channels;
        m.alpha = spec.alpha >= 0 && spec.alpha < spec.channels ? spec.alpha : -1;
        if (spec.channels - (m.alpha >= 0) != 1)
            throw Error(path, not_a_dem(path, spec, spec.channels - (m.alpha >= 0)));
        if (spec.mixed_types || spec.type == backends::SampleType::other)
            throw Error(path, "samples of mixed or unusual types are read whole: give more memory");
        // Half floats widen exactly.
        m.type =
            spec.type == backends::SampleType::float16 ? backends::SampleType::float32 : spec.type;
        m.file_width = spec.width, m.file_height = spec.height;
        if (m.tiff)
            m.geo = read_geotiff_tags(path, spec.width, spec.height, m.tiff->geo_tags());
    }
    // One pass over the file: its voids, and the box of its valid samples (crop_and_fill's).
    int top = m.file_height, bottom = -1, left = m.file_width, right = -1;
    std::int64_t voids = 0;
    const int strip = std::max(1, int((std::int64_t(1) << 20) / m.file_width));
    for (int a = 0; a < m.file_height; a += strip) {
        const RawGrid g = m.oriented(a, std::min(m.file_height, a + strip));
        for (int r = 0; r < g.height; ++r) {
            const std::uint8_t *row = g.is_void.data() + std::size_t(r) * std::size_t(g.width);
            const std::uint8_t *first = std::find(row, row + g.width, 0);
            if (first == row + g.width) {
                voids += g.width;
                continue;
            }
            int last = g.width - 1;
            while (row[last])
                --last;
            voids += std::count(row, row + g.width, 1);
            top = std::min(top, a + r), bottom = a + r;
            left = std::min(left, int(first - row)), right = std::max(right, last);
        }
    }
    if (bottom < 0)
        throw Error(path, "every sample is a void (nodata); there is no terrain to use");
    Heightfield &hf = m.grid;
    hf.voids = voids;
    const int w = right - left + 1, h = bottom - top + 1;
    if (w < m.file_width || h < m.file_height) {
        check_size(path, w, h);
        hf.cropped = std::int64_t(m.file_width) * m.file_height - std::int64_t(w) * h;
        m.geo.west += left * m.geo.sx;
        m.geo.north -= top * m.geo.sy;
    }
    m.left = left, m.top = top;
    // The cropped rows and columns hold only voids.
    hf.filled = voids - hf.cropped;
    if (hf.filled > 0 && !options.fill_voids)
        throw Error(path, std::to_string(hf.filled) + " void samples inside the terrain");
    RawGrid size;
    size.width = w, size.height = h;
    apply_georef(path, m.geo, options, size, hf);
    hf.width = w, hf.height = h;
}

DemWindows::~DemWindows() = default;

const Heightfield &DemWindows::grid() const { return impl_->grid; }

std::vector<float> DemWindows::rows(int r0, int r1) const {
    const Impl &m = *impl_;
    const int h = m.grid.height, w = m.grid.width;
    // The cropped grid's rows run north first.
    const int a = h - r1, b = h - r0;
    RawGrid g = m.cropped(a, b);
    if (std::find(g.is_void.begin(), g.is_void.end(), 1) != g.is_void.end()) {
        // Each strip of k_fill_rows with voids, filled over it and its margins.
        for (int s = a / k_fill_rows; s * k_fill_rows < b; ++s) {
            const int sa = s * k_fill_rows, sb = std::min(h, sa + k_fill_rows);
            const int lo = std::max(a, sa), hi = std::min(b, sb);
            const auto first = g.is_void.begin() + std::ptrdiff_t(lo - a) * w;
            if (std::find(first, first + std::ptrdiff_t(hi - lo) * w, 1) == first + (hi - lo) * w)
                continue;
            const std::lock_guard<std::mutex> guard(m.fill_lock);
            if (m.filled_strip != s) {
                const int wa = std::max(0, sa - k_fill_margin);
                const int wb = std::min(h, sb + k_fill_margin);
                RawGrid f = m.cropped(wa, wb);
                const VoidNumbers voids(f.is_void);
                ring_fill(f, voids);
                harmonic_fill(f, voids);
                m.filled_rows.assign(f.z.begin() + std::ptrdiff_t(sa - wa) * w,
                                     f.z.begin() + std::ptrdiff_t(sb - wa) * w);
                m.filled_strip = s;
            }
            std::copy(m.filled_rows.begin() + std::ptrdiff_t(lo - sa) * w,
                      m.filled_rows.begin() + std::ptrdiff_t(hi - sa) * w,
                      g.z.begin() + std::ptrdiff_t(lo - a) * w);
        }
    }
    mirror(g.z, g.width, g.height, false, true);
    if (m.options.zscale != 1.0)
        for (float &z : g.z)
            z = static_cast<float>(z * m.options.zscale);
    return std::move(g.z);
}

std::int64_t raster_samples(const std::string &path) {
    const std::string ext = lower_extension(path);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw Error(path, "not a regular file");
    if (ext == ".hgt") {
        const auto bytes = fs::file_size(path, ec);
        const auto side = std::int64_t(std::llround(std::sqrt(double(ec ? 0 : bytes) / 2.0)));
        return side * side;
    }
    if (ext == ".tif" || ext == ".tiff")
        if (const auto tiff = backends::tiff_files().open(path))
            if (const auto layout = tiff->layout())
                return std::int64_t(layout->width) * std::int64_t(layout->height);
    const auto file = backends::image_files().open_raster(path);
    return std::int64_t(file->spec().width) * file->spec().height;
}

} // namespace tinlod
