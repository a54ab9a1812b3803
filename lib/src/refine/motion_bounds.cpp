// Bounds carried from view to view (motion_bounds.hpp).
#include "refine/motion_bounds.hpp"

namespace tinlod::refine {

using namespace erase;

void seen_before(EraserState &s, const Hole &h, std::array<double, k_max_ring> &old) {
    const bool kept = !s.fans_stale && keeps_bounds(s);
    for (int i = 0; i < h.n; ++i)
        old[std::size_t(i)] = kept ? seen_now(s, live_node(s, node_of(s, h.r[i]))) : INFINITY;
}

void carry_seen(EraserState &s, const Hole &h, const std::array<double, k_max_ring> &old) {
    const double cost = h.cost > 0.0 ? std::log(h.cost * (1.0 + 1e-6)) : -INFINITY;
    for (int i = 0; i < h.n; ++i) {
        if (!(old[std::size_t(i)] < INFINITY))
            continue;
        LiveNode &l = live_node(s, node_of(s, h.r[i]));
        const glm::dvec3 p = to_glm(l.p), r(double(l.reach));
        l.seen_log = float_up(std::max(old[std::size_t(i)], cost) + 1e-6);
        l.seen_at = s.updates;
        l.seen_cone = s.weigher.in_cone(p - r, p + r);
    }
}

double seen_bound(const EraserState &s, FH f, const glm::dvec3 &lo, const glm::dvec3 &hi) {
    if (s.face_seen_dev[f.idx()] < 0.0f)
        return INFINITY;
    const EraserState::Since *d = since(s, s.face_seen[f.idx()] >> 1);
    if (!d)
        return INFINITY;
    const double nearest = glm::length(glm::clamp(s.view.eye, lo, hi) - s.view.eye);
    return double(s.face_seen_dev[f.idx()]) *
           weight_growth(s, *d, nearest, s.face_seen[f.idx()] & 1) * k_rounded_weight *
           (1.0 + 1e-9);
}

void remember_seen(EraserState &s, FH f, double seen, const glm::dvec3 &lo, const glm::dvec3 &hi) {
    s.face_seen_dev[f.idx()] = float_up(seen * (1.0 + 1e-9));
    s.face_seen[f.idx()] = s.updates << 1 | std::uint32_t(s.weigher.in_cone(lo, hi));
}

} // namespace tinlod::refine
