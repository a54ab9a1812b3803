// The OpenImageIO backend (backends.hpp): rasters and images of every format it reads or writes,
// and image comparison.
#include "backends.hpp"
#include "tinlod/error.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

namespace tinlod::backends {

namespace {

// Sends the process's stderr to /dev/null while it lives: libpng prints its errors there itself
// ("libpng error: IDAT: Read error: hit end of file"), beside the one line tinlod prints for the
// same error from what OpenImageIO reports.
class QuietStderr {
  public:
    QuietStderr() : saved_(::dup(STDERR_FILENO)) {
        const int null = ::open("/dev/null", O_WRONLY);
        if (saved_ >= 0 && null >= 0)
            ::dup2(null, STDERR_FILENO);
        if (null >= 0)
            ::close(null);
    }
    ~QuietStderr() {
        if (saved_ < 0)
            return;
        ::dup2(saved_, STDERR_FILENO);
        ::close(saved_);
    }
    QuietStderr(const QuietStderr &) = delete;
    QuietStderr &operator=(const QuietStderr &) = delete;

  private:
    int saved_;
};

SampleType sample_type(OIIO::TypeDesc t) {
    switch (t.basetype) {
    case OIIO::TypeDesc::UINT8:
        return SampleType::uint8;
    case OIIO::TypeDesc::INT8:
        return SampleType::int8;
    case OIIO::TypeDesc::UINT16:
        return SampleType::uint16;
    case OIIO::TypeDesc::INT16:
        return SampleType::int16;
    case OIIO::TypeDesc::UINT32:
        return SampleType::uint32;
    case OIIO::TypeDesc::INT32:
        return SampleType::int32;
    case OIIO::TypeDesc::HALF:
        return SampleType::float16;
    case OIIO::TypeDesc::FLOAT:
        return SampleType::float32;
    case OIIO::TypeDesc::DOUBLE:
        return SampleType::float64;
    default:
        return SampleType::other;
    }
}

OIIO::TypeDesc type_desc(SampleType t) {
    switch (t) {
    case SampleType::uint8:
        return OIIO::TypeDesc::UINT8;
    case SampleType::int8:
        return OIIO::TypeDesc::INT8;
    case SampleType::uint16:
        return OIIO::TypeDesc::UINT16;
    case SampleType::int16:
        return OIIO::TypeDesc::INT16;
    case SampleType::uint32:
        return OIIO::TypeDesc::UINT32;
    case SampleType::int32:
        return OIIO::TypeDesc::INT32;
    case SampleType::float16:
        return OIIO::TypeDesc::HALF;
    case SampleType::float64:
        return OIIO::TypeDesc::DOUBLE;
    default:
        return OIIO::TypeDesc::FLOAT;
    }
}

class OiioRaster final : public RasterFile {
  public:
    OiioRaster(std::string path, std::unique_ptr<OIIO::ImageInput> in)
        : path_(std::move(path)), in_(std::move(in)) {
        const OIIO::ImageSpec &s = in_->spec();
        spec_.width = s.width;
        spec_.height = s.height;
        spec_.depth = s.depth;
        spec_.channels = s.nchannels;
        spec_.alpha = s.alpha_channel;
        spec_.type = sample_type(s.format);
        spec_.type_bytes = int(s.format.size());
        spec_.type_name = s.format.c_str();
        spec_.mixed_types = !s.channelformats.empty();
    }
    const RasterSpec &spec() const override { return spec_; }
    bool read(SampleType type, void *out) override {
        const QuietStderr quiet;
        // Samples already of the asked type are read as they are (UNKNOWN): naming the type sends
        // OpenImageIO 2.4 through its conversion path, with a 64 MiB scratch buffer per read
        // whatever the size of the image.
        const bool native = type == spec_.type && !spec_.mixed_types;
        // OpenImageIO 2.4 reports a TIFF strip it could not read (a truncated file) as an error
        // pending on the reader, yet returns success with zeros in its place.
        if (!in_->read_image(0, 0, 0, spec_.channels,
                             native ? OIIO::TypeDesc::UNKNOWN : type_desc(type), out) ||
            in_->has_error()) {
            std::string why = in_->geterror();
            const auto nl = why.find('\n');
            throw Error(path_, "cannot read samples (truncated or corrupt): " + why.substr(0, nl));
        }
        return true;
    }
    bool read_window(int y0, int y1, SampleType type, void *out) override {
        const QuietStderr quiet;
        // A tiled file's rows come from the tiles they cross (OpenImageIO reads those tiles).
        const bool native = type == spec_.type && !spec_.mixed_types;
        const OIIO::TypeDesc as = native ? OIIO::TypeDesc::UNKNOWN : type_desc(type);
        const OIIO::ImageSpec &s = in_->spec();
        bool ok = true;
        if (s.tile_width > 0 && s.tile_height > 0) {
            // A tiled file reads whole rows of tiles: those holding rows y0 .. y1 - 1.
            const int t0 = y0 / s.tile_height * s.tile_height;
            const int t1 =
                std::min(s.height, (y1 + s.tile_height - 1) / s.tile_height * s.tile_height);
            const std::size_t row = std::size_t(s.width) * std::size_t(spec_.channels) *
                                    std::size_t(type_desc(type).size());
            // The last rows of tiles read are kept: the next window often falls in them.
            if (t0 != tiles_from_ || t1 != tiles_to_ || type != tiles_type_) {
                tiles_from_ = tiles_to_ = -1;
                tiles_.resize(row * std::size_t(t1 - t0));
                ok = in_->read_tiles(0, 0, 0, s.width, t0, t1, 0, 1, 0, spec_.channels, as,
                                     tiles_.data());
                if (ok)
                    tiles_from_ = t0, tiles_to_ = t1, tiles_type_ = type;
            }
            std::memcpy(out, tiles_.data() + row * std::size_t(y0 - t0),
                        row * std::size_t(y1 - y0));
        } else {
            ok = in_->read_scanlines(0, 0, y0, y1, 0, 0, spec_.channels, as, out);
        }
        if (!ok || in_->has_error()) {
            std::string why = in_->geterror();
            const auto nl = why.find('\n');
            throw Error(path_, "cannot read rows " + std::to_string(y0) + " to " +
                                   std::to_string(y1 - 1) +
                                   " (truncated or corrupt): " + why.substr(0, nl));
        }
        return true;
    }

  private:
    std::string path_;
    std::unique_ptr<OIIO::ImageInput> in_;
    RasterSpec spec_;
    std::vector<unsigned char> tiles_; // rows tiles_from_ .. tiles_to_ - 1 of tiles, as read
    int tiles_from_ = -1, tiles_to_ = -1;
    SampleType tiles_type_ = SampleType::other;
};

OIIO::ImageBuf wrap(const PixelView &p) {
    const OIIO::ImageSpec spec(p.width, p.height, p.channels, OIIO::TypeDesc::UINT8);
    return OIIO::ImageBuf(spec, const_cast<void *>(p.data));
}

OIIO::ROI rgb(const PixelView &p) { return OIIO::ROI(0, p.width, 0, p.height, 0, 1, 0, 3); }

class Oiio final : public ImageFiles {
  public:
    void set_threads(int threads) override {
        OIIO::attribute("threads", threads);
        OIIO::attribute("exr_threads", threads);
    }

    std::unique_ptr<RasterFile> open_raster(const std::string &path) override {
        const QuietStderr quiet;
        // Alpha as stored: by default OpenImageIO multiplies the other channels by it, and reads a
        // PNG's tRNS key as alpha 0 (so the key's heights came out as 0 m).
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        auto in = OIIO::ImageInput::open(path, &config);
        if (!in) {
            std::string why = OIIO::geterror();
            if (why.empty())
                why = "not a readable raster";
            const auto nl = why.find('\n');
            throw Error(path, "cannot read raster: " + why.substr(0, nl));
        }
        return std::make_unique<OiioRaster>(path, std::move(in));
    }

    void write_image(const std::string &path, const std::string &tmp,
                     const PixelView &pixels) override {
        auto out = OIIO::ImageOutput::create(tmp);
        if (!out)
            throw Error(path, "cannot write this image format (" + OIIO::geterror() + ")");
        // Encoded in memory, then written through a stream whose state is checked: OpenImageIO's
        // file writers report success on a full disk, with a short file.
        std::vector<unsigned char> bytes;
        OIIO::Filesystem::IOVecOutput memory(bytes);
        const bool in_memory = out->supports("ioproxy") && out->set_ioproxy(&memory);
        const OIIO::TypeDesc type =
            pixels.float_samples ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
        const OIIO::ImageSpec spec(pixels.width, pixels.height, pixels.channels, type);
        if (!out->open(tmp, spec) || !out->write_image(type, pixels.data) || !out->close())
            throw Error(path, "cannot write the image: " + out->geterror());
        if (in_memory) {
            std::ofstream file(tmp, std::ios::binary);
            file.write(reinterpret_cast<const char *>(bytes.data()), std::streamsize(bytes.size()));
            if (!file.flush())
                throw Error(path, "cannot write the image: " + std::string(std::strerror(errno)));
        }
    }

    std::vector<std::uint8_t> read_image(const std::string &path, int &width, int &height,
                                         int &channels) override {
        auto in = OIIO::ImageInput::open(path);
        if (!in)
            throw Error(path, "cannot read the image: " + OIIO::geterror());
        const OIIO::ImageSpec &spec = in->spec();
        width = spec.width;
        height = spec.height;
        channels = spec.nchannels;
        if (spec.width <= 0 || spec.height <= 0 || channels <= 0)
            throw Error(path, "empty image");
        std::vector<std::uint8_t> pixels(std::size_t(spec.width) * spec.height * channels);
        if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data()) ||
            in->has_error())
            throw Error(path, "cannot read the image: " + in->geterror());
        return pixels;
    }

    CompareResults compare(const PixelView &a, const PixelView &b, float fail) override {
        const OIIO::ImageBuf A = wrap(a), B = wrap(b);
        const OIIO::ImageBufAlgo::CompareResults r =
            OIIO::ImageBufAlgo::compare(A, B, fail, fail, rgb(a));
        // `error` is also set when some pixel fails the threshold; only without failures is it
        // real.
        if (r.error && r.nfail == 0)
            throw Error("compare", "OpenImageIO cannot compare the images: " + OIIO::geterror());
        CompareResults c;
        c.mean = r.meanerror;
        c.rms = r.rms_error;
        c.psnr = r.PSNR;
        c.max = r.maxerror;
        c.failures = static_cast<std::int64_t>(r.nfail);
        return c;
    }

    std::vector<float> absdiff(const PixelView &a, const PixelView &b) override {
        const OIIO::ImageBuf A = wrap(a), B = wrap(b);
        const OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(A, B, rgb(a));
        if (diff.has_error())
            throw Error("compare", "OpenImageIO cannot subtract the images: " + diff.geterror());
        std::vector<float> values(std::size_t(a.width) * a.height * 3);
        diff.get_pixels(rgb(a), OIIO::TypeDesc::FLOAT, values.data());
        return values;
    }
};

} // namespace

extern "C" ImageFiles *tinlod_oiio_backend() {
    static Oiio backend;
    return &backend;
}

} // namespace tinlod::backends
