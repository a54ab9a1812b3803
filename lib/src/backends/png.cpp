// The libpng backend (backends.hpp): PNG rasters read with the transformations OpenImageIO's PNG
// reader asks of libpng (png_set_expand: palette to RGB, 1/2/4-bit grey to 8 bits, tRNS to
// alpha; samples in the host's byte order), so that they come out as OpenImageIO reads them.
// Interlaced files, and any file libpng reports an error on, are left to OpenImageIO.
#include "backends.hpp"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>

namespace tinlod::backends {

namespace {

void on_error(png_structp png, png_const_charp) { png_longjmp(png, 1); }
void on_warning(png_structp, png_const_charp) {}

// libpng reports errors by longjmp: the functions that call it hold nothing with a destructor.
bool read_header(png_structp png, png_infop info, RasterSpec &spec) {
    if (setjmp(png_jmpbuf(png)))
        return false;
    png_read_info(png, info);
    png_set_expand(png);
    png_set_swap(png); // 16-bit samples big-endian in the file, the host's order in memory
    png_read_update_info(png, info);
    png_uint_32 width = 0, height = 0;
    int bit_depth = 0, color_type = 0;
    if (!png_get_IHDR(png, info, &width, &height, &bit_depth, &color_type, nullptr, nullptr,
                      nullptr) ||
        png_get_interlace_type(png, info) != PNG_INTERLACE_NONE)
        return false;
    spec.width = int(width);
    spec.height = int(height);
    spec.channels = png_get_channels(png, info);
    spec.type = bit_depth == 16 ? SampleType::uint16 : SampleType::uint8;
    spec.type_bytes = bit_depth == 16 ? 2 : 1;
    spec.type_name = bit_depth == 16 ? "uint16" : "uint8";
    // OpenImageIO's channel names: grey + alpha, or R, G, B, A.
    spec.alpha = spec.channels == 2 ? 1 : spec.channels >= 4 ? 3 : -1;
    return spec.width > 0 && spec.height > 0 && spec.channels > 0;
}

bool read_rows(png_structp png, unsigned char *out, std::size_t row_bytes, int rows) {
    if (setjmp(png_jmpbuf(png)))
        return false;
    for (int r = 0; r < rows; ++r)
        png_read_row(png, out + std::size_t(r) * row_bytes, nullptr);
    return true;
}

class PngRaster final : public RasterFile {
  public:
    PngRaster(std::FILE *file, png_structp png, png_infop info)
        : file_(file), png_(png), info_(info) {}
    ~PngRaster() override {
        png_destroy_read_struct(&png_, &info_, nullptr);
        std::fclose(file_);
    }
    PngRaster(const PngRaster &) = delete;
    PngRaster &operator=(const PngRaster &) = delete;

    bool open() { return read_header(png_, info_, spec_); }
    const RasterSpec &spec() const override { return spec_; }
    bool read(SampleType type, void *out) override {
        if (type != spec_.type)
            return false;
        const std::size_t row_bytes =
            std::size_t(spec_.width) * spec_.channels * (spec_.type == SampleType::uint16 ? 2 : 1);
        return row_bytes == png_get_rowbytes(png_, info_) &&
               read_rows(png_, static_cast<unsigned char *>(out), row_bytes, spec_.height);
    }

  private:
    std::FILE *file_;
    png_structp png_;
    png_infop info_;
    RasterSpec spec_;
};

class Png final : public PngFiles {
  public:
    std::unique_ptr<RasterFile> open_raster(const std::string &path) override {
        std::FILE *file = std::fopen(path.c_str(), "rb");
        if (!file)
            return nullptr;
        unsigned char signature[8] = {};
        if (std::fread(signature, 1, sizeof signature, file) != sizeof signature ||
            png_sig_cmp(signature, 0, sizeof signature) != 0) {
            std::fclose(file);
            return nullptr;
        }
        png_structp png =
            png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, on_error, on_warning);
        png_infop info = png ? png_create_info_struct(png) : nullptr;
        if (!info) {
            png_destroy_read_struct(&png, nullptr, nullptr);
            std::fclose(file);
            return nullptr;
        }
        png_init_io(png, file);
        png_set_sig_bytes(png, sizeof signature);
        auto raster = std::make_unique<PngRaster>(file, png, info);
        return raster->open() ? std::move(raster) : nullptr;
    }
};

} // namespace

extern "C" PngFiles *tinlod_png_backend() {
    static Png backend;
    return &backend;
}

} // namespace tinlod::backends
