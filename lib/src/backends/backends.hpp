// The libraries tinlod needs only for some files and commands, each behind one interface:
// OpenImageIO (image files of every kind), libtiff (GeoTIFF), libpng (PNG) and PROJ (coordinate
// reference systems). The installed libraries link them (linked.cpp); the command line opens each
// from a module beside the program the first time a file needs it (modules.cpp), so that a
// command loads only what its inputs and outputs use (docs/decisions/020-startup.md).
//
// A module is built from the same backend source as the linked library and shares no state with
// the program: everything it needs arrives as arguments, and it reports bad files by throwing
// tinlod::Error.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tinlod::backends {

// --- Rasters: what a file holds, read by any of the readers below. ---

enum class SampleType : std::uint8_t {
    uint8,
    int8,
    uint16,
    int16,
    uint32,
    int32,
    float16,
    float32,
    float64,
    other
};

// A raster file's layout as OpenImageIO describes it; the faster readers describe the files they
// accept exactly as OpenImageIO would.
struct RasterSpec {
    int width = 0;
    int height = 0;
    int depth = 1;    // > 1: a volume
    int channels = 0; // samples per pixel
    int alpha = -1;   // the alpha channel, or -1
    SampleType type = SampleType::other;
    int type_bytes = 1;       // of a sample
    std::string type_name;    // the sample type as OpenImageIO names it ("uint16", "float"), for
                              // messages
    bool mixed_types = false; // channels of different types
};

class RasterFile {
  public:
    virtual ~RasterFile() = default;
    virtual const RasterSpec &spec() const = 0;
    // Reads every channel of every pixel, the file's first row first, into `out` (room for
    // width * height * channels samples of `type`). `type` is spec().type, or float32 to have the
    // samples converted. Returns false when this reader declines the file after all (only the
    // faster readers do: OpenImageIO then reads it); throws Error naming the file when the file
    // is bad.
    virtual bool read(SampleType type, void *out) = 0;
    // Reads rows [y0, y1) alike (every channel, `type` the file's own), and only those, for a
    // raster read by windows; false when this reader reads only whole images.
    virtual bool read_window(int y0, int y1, SampleType type, void *out) {
        (void)y0, (void)y1, (void)type, (void)out;
        return false;
    }
};

// --- OpenImageIO: rasters and images of every format it knows. ---

// Pixels of 8-bit or float samples, rows top-down, channels interleaved.
struct PixelView {
    int width = 0;
    int height = 0;
    int channels = 0;
    bool float_samples = false;
    const void *data = nullptr;
};

// ImageBufAlgo::compare's results over the RGB channels, values in 0..1 of full scale.
struct CompareResults {
    double mean = 0, rms = 0, psnr = 0, max = 0;
    std::int64_t failures = 0;
};

class ImageFiles {
  public:
    virtual ~ImageFiles() = default;
    // Sets the threads OpenImageIO and OpenEXR may use.
    virtual void set_threads(int threads) = 0;
    // Opens any raster OpenImageIO reads (alpha as stored, not multiplied into the heights);
    // throws Error(path, "cannot read raster: ...").
    virtual std::unique_ptr<RasterFile> open_raster(const std::string &path) = 0;
    // Writes `pixels` to `tmp` in the format `tmp`'s extension names, `path` being the name that
    // errors give. Throws Error when the format or the write fails.
    virtual void write_image(const std::string &path, const std::string &tmp,
                             const PixelView &pixels) = 0;
    // An image file's pixels as 8-bit samples, any number of channels; throws Error naming it.
    virtual std::vector<std::uint8_t> read_image(const std::string &path, int &width, int &height,
                                                 int &channels) = 0;
    // Compares the RGB channels of two RGBA8 images of one size, a channel failing above `fail`
    // (0..1 of full scale).
    virtual CompareResults compare(const PixelView &a, const PixelView &b, float fail) = 0;
    // |a - b| of the RGB channels of two RGBA8 images of one size, 0..1 of full scale, 3 floats a
    // pixel; throws Error("compare", ...) when it fails.
    virtual std::vector<float> absdiff(const PixelView &a, const PixelView &b) = 0;
};

// --- libtiff: a TIFF's layout and GeoTIFF tags, and its samples when they are plain. ---

// A TIFF's declared size and sample layout, read before anything allocates for it.
struct TiffLayout {
    std::uint32_t width = 0, height = 0;
    std::uint16_t samples_per_pixel = 1, bits_per_sample = 8;
    bool tiled = false; // tile_width x tile_height tiles, else strips
    std::uint32_t tile_width = 0, tile_height = 0;
};

// The georeferencing tags of a GeoTIFF, as stored (empty where absent).
struct GeoTags {
    // GeoKeys of type SHORT, as libgeotiff's GTIFKeyGetSHORT reads them (absent when the key
    // directory is unreadable).
    std::optional<std::uint16_t> model, raster, geographic_type, projected_type;
    std::vector<double> pixel_scale;   // ModelPixelScale (33550)
    std::vector<double> tie_points;    // ModelTiepoint (33922)
    std::vector<double> matrix;        // ModelTransformation (34264)
    std::optional<std::string> nodata; // GDAL_NODATA (42113) text
};

class TiffFile {
  public:
    virtual ~TiffFile() = default;
    // Width and height are missing: nothing else can be trusted.
    virtual std::optional<TiffLayout> layout() = 0;
    virtual GeoTags geo_tags() = 0;
    // A reader of the first image, when its samples are plain (one channel of 8 to 64 bits, a
    // compression libtiff decodes, nothing OpenImageIO would convert); nullptr otherwise.
    virtual std::unique_ptr<RasterFile> raster() = 0;
};

class TiffFiles {
  public:
    virtual ~TiffFiles() = default;
    // nullptr when libtiff cannot open `path` as a TIFF. `mapped`: libtiff maps the whole file
    // into memory (its default); a file read by windows is not, so that only the windows it
    // reads are resident.
    virtual std::unique_ptr<TiffFile> open(const std::string &path, bool mapped = true) = 0;
};

// --- libpng: PNG files that are not interlaced. ---

class PngFiles {
  public:
    virtual ~PngFiles() = default;
    // A reader of `path` when it is a PNG this reader takes (not interlaced), nullptr otherwise.
    virtual std::unique_ptr<RasterFile> open_raster(const std::string &path) = 0;
};

// --- PROJ: any coordinate reference system of its database. ---

// A transformation between two CRSs, made once (PROJ reads its database) and applied to many
// points.
class CrsTransformation {
  public:
    virtual ~CrsTransformation() = default;
    // Transforms `points` in place; one PROJ cannot transform becomes non-finite.
    virtual void apply(std::span<std::array<double, 2>> points) const = 0;
};

class CrsLibrary {
  public:
    virtual ~CrsLibrary() = default;
    // Throws Error(path, ...) when PROJ does not know EPSG:`epsg` as a CRS of the kind the file
    // says (`geographic` or projected), or when a projected one measures in other units than
    // metres.
    virtual void check_crs(const std::string &path, int epsg, bool geographic) = 0;
    // The transformation from EPSG:`from` to EPSG:`to` that PROJ's proj_create_crs_to_crs makes,
    // x east / longitude first whatever the CRSs' axis order. Throws Error(path, ...) when PROJ
    // has none.
    virtual std::unique_ptr<CrsTransformation> transformation(const std::string &path, int from,
                                                              int to) = 0;
};

// Each backend, made ready for use: the linked ones, or the command line's modules (loaded the
// first time; a missing or broken module is an Error naming it). image_files() also applies
// max_threads().
ImageFiles &image_files();
TiffFiles &tiff_files();
PngFiles &png_files();
CrsLibrary &crs_library();

// How each backend source hands out its implementation: the linked library calls these, a
// module exports the one it holds (modules.cpp looks it up by this name).
extern "C" {
ImageFiles *tinlod_oiio_backend();
TiffFiles *tinlod_tiff_backend();
PngFiles *tinlod_png_backend();
CrsLibrary *tinlod_proj_backend();
}

} // namespace tinlod::backends
