// Image error between two renders of the same view (a TIN against the full-resolution reference),
// computed by OpenImageIO's ImageBufAlgo::compare over the RGB channels.
#pragma once

#include "tinlod/render.hpp"

#include <cstdint>

namespace tinlod {

struct ImageCompareOptions {
    double threshold = 2.0; // grey levels (0..255): a pixel differs when one of its R, G, B
                            // channels differs by more than this
};

struct ImageDifference {
    double psnr_db = 0.0;              // 20 log10(255 / RMS), dB over R, G, B; +infinity if equal
    double rms = 0.0;                  // grey levels, over every R, G, B value
    double mean = 0.0;                 // grey levels, mean absolute difference over R, G, B values
    double max = 0.0;                  // grey levels, the largest channel difference
    std::int64_t differing_pixels = 0; // pixels with a channel differing by more than threshold
    double differing_share = 0.0;      // differing_pixels / pixels, 0..1
};

// Compares two images of the same size; throws Error("compare", ...) when the sizes differ.
ImageDifference compare_images(const Image &a, const Image &b,
                               const ImageCompareOptions &options = {});

// |a - b| per R, G, B channel, multiplied by `gain` (so small differences show) and clamped;
// opaque. Same size required, as for compare_images.
Image difference_image(const Image &a, const Image &b, double gain = 8.0);

} // namespace tinlod
