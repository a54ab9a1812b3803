// Image error between renders (image_metrics.hpp) through OpenImageIO's ImageBufAlgo::compare and
// ImageBufAlgo::absdiff (src/backends/oiio.cpp).
#include "tinlod/image_metrics.hpp"
#include "backends/backends.hpp"
#include "tinlod/error.hpp"

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

backends::PixelView pixels(const Image &image) {
    return {image.width, image.height, 4, false, image.rgba.data()};
}

} // namespace

ImageDifference compare_images(const Image &a, const Image &b, const ImageCompareOptions &options) {
    check_same_size(a, b);
    // OpenImageIO reads 8-bit values as v / 255; half a level above the threshold makes "differs
    // by more than t levels" exact for integer t despite rounding.
    const float fail = float((options.threshold + 0.5) / 255.0);
    const backends::CompareResults r = backends::image_files().compare(pixels(a), pixels(b), fail);
    ImageDifference d;
    d.rms = r.rms * 255.0;
    d.mean = r.mean * 255.0;
    d.max = r.max * 255.0;
    d.psnr_db = r.rms > 0.0 ? r.psnr : std::numeric_limits<double>::infinity();
    d.differing_pixels = r.failures;
    const double pixels = double(a.width) * a.height;
    d.differing_share = pixels > 0 ? double(d.differing_pixels) / pixels : 0.0;
    return d;
}

Image difference_image(const Image &a, const Image &b, double gain) {
    check_same_size(a, b);
    const std::vector<float> values = backends::image_files().absdiff(pixels(a), pixels(b));
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
