// Bounds carried from view to view (motion_bounds.hpp).
#include "refine/motion_bounds.hpp"

namespace tinlod::refine {

using namespace erase;

double seen_bound(const EraserState &s, FH f, const glm::dvec3 &lo, const glm::dvec3 &hi) {
    if (s.seen.face_seen_dev[f.idx()] < 0.0f)
        return INFINITY;
    const ViewBounds::Since *d = since(s, s.seen.face_seen[f.idx()] >> 1);
    if (!d)
        return INFINITY;
    const double nearest = glm::length(glm::clamp(s.view.eye, lo, hi) - s.view.eye);
    return double(s.seen.face_seen_dev[f.idx()]) *
           weight_growth(s, *d, nearest, s.seen.face_seen[f.idx()] & 1) * k_rounded_weight *
           (1.0 + 1e-9);
}

void remember_seen(EraserState &s, FH f, double seen, const glm::dvec3 &lo, const glm::dvec3 &hi) {
    s.seen.face_seen_dev[f.idx()] = float_up(seen * (1.0 + 1e-9));
    s.seen.face_seen[f.idx()] = s.seen.updates << 1 | std::uint32_t(s.weigher.in_cone(lo, hi));
}

} // namespace tinlod::refine
