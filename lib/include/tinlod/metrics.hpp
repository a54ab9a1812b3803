// Geometric error of a TIN against its DEM, exhaustive over every sample (the yardstick of every
// bound tinlod claims), in world units and in screen pixels for a view.
#pragma once

#include "tinlod/raster.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <cstdint>

namespace tinlod {

struct TinError {
    // L-infinity of |z_sample - z_tin| over every covered sample, world units
    double max_vertical = 0.0;
    double rms_vertical = 0.0; // RMS of the same
    // max over samples inside the frustum of |dz| * k / distance(eye, sample)
    double max_screen_px = 0.0;
    std::int64_t samples = 0;   // samples covered by the TIN
    std::int64_t uncovered = 0; // samples no triangle covers in xy (0 for a crack-free TIN)
    // sample id (r * width + c) of max_screen_px (or max_vertical without a view)
    std::int64_t worst_sample = -1;
};

struct ErrorOptions {
    // The view of the screen and paper models gives max_screen_px (k / distance, without the
    // peripheral factor); the vertical model (the default) has none: it stays 0.
    Significance model;
    bool frustum_only = true; // screen error only over samples inside the view frustum
};

// Rasterises every live triangle of `tin` (local world frame of `hf`, x = c*dx, y = r*dy) over the
// grid and compares the interpolated height with every sample it covers. Cost O(samples + faces).
TinError measure_error(const Heightfield &hf, const Mesh &tin, const ErrorOptions &options = {});

// The same over a compact TIN: `triangles` holds 3 grid sample ids per triangle.
TinError measure_error(const Heightfield &hf, const std::vector<std::uint32_t> &triangles,
                       const ErrorOptions &options = {});

} // namespace tinlod
