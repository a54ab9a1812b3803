// Bounds carried from view to view (motion_bounds.hpp).
#include "refine/motion_bounds.hpp"

namespace tinlod::refine {

using namespace erase;

double seen_bound(const EraserState &s, const FrameState &frame, FH f, const glm::dvec3 &lo,
                  const glm::dvec3 &hi) {
    if (frame.seen.face_seen_dev[f.idx()] < 0.0f)
        return INFINITY;
    const ViewBounds::Since *d = since(s, frame, frame.seen.face_seen[f.idx()] >> 1);
    if (!d)
        return INFINITY;
    const double nearest = glm::length(glm::clamp(s.weights.view.eye, lo, hi) - s.weights.view.eye);
    return double(frame.seen.face_seen_dev[f.idx()]) *
           weight_growth(s.weights.weigher, *d, nearest, frame.seen.face_seen[f.idx()] & 1) *
           k_rounded_weight * (1.0 + 1e-9);
}

void remember_seen(ViewBounds &bounds, const Weigher &weigher, FH f, double seen,
                   const glm::dvec3 &lo, const glm::dvec3 &hi) {
    bounds.face_seen_dev[f.idx()] = float_up(seen * (1.0 + 1e-9));
    bounds.face_seen[f.idx()] = bounds.updates << 1 | std::uint32_t(weigher.in_cone(lo, hi));
}

} // namespace tinlod::refine
