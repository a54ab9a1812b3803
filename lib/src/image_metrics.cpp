// Image error between renders (image_metrics.hpp) through OpenImageIO's ImageBufAlgo::compare and
// ImageBufAlgo::absdiff.
#include "tinlod/image_metrics.hpp"
#include "oiio_threads.hpp"
#include "tinlod/error.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cassert>
#include <cmath>
#include <limits>

namespace tinlod {

namespace {

void check_same_size(const Image &a, const Image &b) {
    assert(a.rgba.size() == std::size_t(a.width) * a.height * 4);
    assert(b.rgba.size() == std::size_t(b.width) * b.height * 4);
    if (a.width != b.width || a.height != b.height)
        throw Error("compare", "images differ in size: " + std::to_string(a.width) + "x" +
                                   std::to_string(a.height) + " and " + std::to_string(b.width) +
                                   "x" + std::to_string(b.height));
}

// A read-only view of an Image's pixels as an OpenImageIO buffer (no copy).
OIIO::ImageBuf wrap(const Image &image) {
    const OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
    return OIIO::ImageBuf(spec, const_cast<std::uint8_t *>(image.rgba.data()));
}

OIIO::ROI rgb(const Image &image) { return OIIO::ROI(0, image.width, 0, image.height, 0, 1, 0, 3); }

} // namespace

ImageDifference compare_images(const Image &a, const Image &b, const ImageCompareOptions &options) {
    check_same_size(a, b);
    limit_oiio_threads();
    const OIIO::ImageBuf A = wrap(a), B = wrap(b);
    // OpenImageIO reads 8-bit values as v / 255; half a level above the threshold makes "differs
    // by more than t levels" exact for integer t despite rounding.
    const float fail = float((options.threshold + 0.5) / 255.0);
    const OIIO::ImageBufAlgo::CompareResults r =
        OIIO::ImageBufAlgo::compare(A, B, fail, fail, rgb(a));
    // `error` is also set when some pixel fails the threshold; only without failures is it real.
    if (r.error && r.nfail == 0)
        throw Error("compare", "OpenImageIO cannot compare the images: " + OIIO::geterror());
    ImageDifference d;
    d.rms = r.rms_error * 255.0;
    d.mean = r.meanerror * 255.0;
    d.max = r.maxerror * 255.0;
    d.psnr_db = r.rms_error > 0.0 ? r.PSNR : std::numeric_limits<double>::infinity();
    d.differing_pixels = static_cast<std::int64_t>(r.nfail);
    const double pixels = double(a.width) * a.height;
    d.differing_share = pixels > 0 ? double(d.differing_pixels) / pixels : 0.0;
    return d;
}

Image difference_image(const Image &a, const Image &b, double gain) {
    check_same_size(a, b);
    limit_oiio_threads();
    const OIIO::ImageBuf A = wrap(a), B = wrap(b);
    const OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(A, B, rgb(a));
    if (diff.has_error())
        throw Error("compare", "OpenImageIO cannot subtract the images: " + diff.geterror());
    std::vector<float> values(std::size_t(a.width) * a.height * 3);
    diff.get_pixels(rgb(a), OIIO::TypeDesc::FLOAT, values.data());
    Image out;
    out.width = a.width;
    out.height = a.height;
    out.rgba.resize(std::size_t(a.width) * a.height * 4);
    for (std::size_t i = 0, n = std::size_t(a.width) * a.height; i < n; ++i) {
        for (int c = 0; c < 3; ++c)
            out.rgba[4 * i + c] = static_cast<std::uint8_t>(
                std::lround(std::min(255.0, values[3 * i + c] * 255.0 * gain)));
        out.rgba[4 * i + 3] = 255;
    }
    return out;
}

} // namespace tinlod
