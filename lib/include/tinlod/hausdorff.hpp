// Symmetric Hausdorff distance between two general triangle meshes, sampled: points spread over
// the faces of each mesh by area (plus every vertex), and for each the exact distance to the
// nearest point of the other mesh's surface through a bounding-volume hierarchy over triangles.
#pragma once

#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <cstdint>

namespace tinlod {

struct HausdorffOptions {
    std::int64_t samples = 200000; // points per mesh spread over its faces by area (its vertices
                                   // are added to these)
    std::uint64_t seed = 1;        // the same seed gives the same points, so the same result
    // The view of the screen and paper models: the screen-space distance too, each sample's
    // distance seen from where it lies (d * k / OD, View::screen_px), over the samples of both
    // directions inside the frustum. The vertical model (the default) has no view.
    Significance model;
};

struct HausdorffResult {
    double max = 0.0;  // symmetric Hausdorff distance: max(a_to_b.max, b_to_a.max), world units
    double mean = 0.0; // mean distance over the samples of both directions, world units
    double rms = 0.0;  // RMS of the same
    double max_a_to_b = 0.0; // largest distance from a sample of a to the surface of b
    double max_b_to_a = 0.0;
    double mean_a_to_b = 0.0;
    double mean_b_to_a = 0.0;
    std::int64_t samples = 0;          // points measured, both directions together
    double max_screen_px = 0.0;        // with a view: the largest screen-space distance, pixels
    double max_screen_px_a_to_b = 0.0; // of a's samples to b's surface
    double max_screen_px_b_to_a = 0.0;
};

// Faces with the deleted status are ignored. Throws Error("hausdorff", ...) when a mesh has no
// live face. Uses every hardware thread; the result does not depend on their number.
HausdorffResult hausdorff(const Mesh &a, const Mesh &b, const HausdorffOptions &options = {});

} // namespace tinlod
