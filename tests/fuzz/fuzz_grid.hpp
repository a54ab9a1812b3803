// Shared by the fuzz targets that build small grids (fuzz_erase, fuzz_greedy): the grid's shape
// first, its heights last, so a short input leaves the rest of the grid flat.
#pragma once

#include "tinlod/raster.hpp"

#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace tinlod::fuzz {

// A grid of 2 to max_side samples a side, one of a few cell sizes, and a height scale (returned);
// its heights are not read yet (take_heights).
inline double take_grid(FuzzedDataProvider &in, int max_side, Heightfield &hf) {
    hf.width = in.ConsumeIntegralInRange(2, max_side);
    hf.height = in.ConsumeIntegralInRange(2, max_side);
    static constexpr double k_cell[] = {1, 0.5, 3, 30};
    hf.dx = in.PickValueInArray(k_cell);
    hf.dy = in.PickValueInArray(k_cell);
    static constexpr double k_zscale[] = {1, 0.01, 10, 1000};
    return in.PickValueInArray(k_zscale);
}

// The grid's heights, one signed byte times zscale each; returns the largest |height|.
inline double take_heights(FuzzedDataProvider &in, double zscale, Heightfield &hf) {
    hf.z.resize(std::size_t(hf.width) * hf.height);
    double max_abs_z = 0;
    for (float &z : hf.z) {
        z = float(in.ConsumeIntegral<std::int8_t>() * zscale);
        max_abs_z = std::max(max_abs_z, double(std::abs(z)));
    }
    return max_abs_z;
}

} // namespace tinlod::fuzz
