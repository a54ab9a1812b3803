// Bounds that carry over from one view to the next: how much a node's weight can have grown or
// shrunk since the view of an earlier update, as the eye moved and the axis turned, so that the
// bounds an update made (a face's or a fan's largest weighted deviation, a node's least cost) are
// tested under the new view without weighing their nodes again.
#pragma once

#include "erase/erase_cost.hpp"
#include "erase/state.hpp"
#include "refine/frame_state.hpp"

#include <array>
#include <cmath>
#include <cstdint>

namespace tinlod::refine {

// The eraser's names the refiner's stages use (they work on the eraser's state).
using erase::EraserState;
using erase::FH;
using erase::float_down;
using erase::float_up;
using erase::Hole;
using erase::k_rounded_weight;
using erase::k_seen_views;
using erase::to_glm;

// Whether the bounds an update makes carry over to the updates that follow (the screen model's, see
// ViewBounds::face_seen_dev and FanBounds::seen_log).
inline bool keeps_bounds(const EraserState &s, const FrameState &frame) {
    return s.weights.model == SpModel::screen && frame.seen.updates > 0;
}

// Live node l's erase cost under the current view is at least `cost` (see FanBounds::low_log).
inline void remember_low(const EraserState &s, const FrameState &frame, FanBounds &l, double cost) {
    l.low_log = -INFINITY;
    if (keeps_bounds(s, frame)) {
        l.low_log = float_down(std::log(cost) - 1e-6);
        l.low_at = frame.seen.updates;
    }
}

// The eye's move and the axis's turn since the view of update `at`, or null when a bound made under
// that view does not carry over to the current one.
inline const ViewBounds::Since *since(const EraserState &s, const FrameState &frame,
                                      std::uint32_t at) {
    if (!keeps_bounds(s, frame) || at == 0 || frame.seen.updates - at >= k_seen_views)
        return nullptr;
    const ViewBounds::Since &d = frame.seen.since[at % k_seen_views];
    return d.ok ? &d : nullptr;
}

// The factor by which the weight of a node at least `nearest` from the current eye may have grown
// since `d` (see ViewBounds::face_seen_dev); infinite when the eye moved that far. `cone`: the
// node was inside the view cone then (peripheral factor 1, which no view exceeds): the distance's
// share alone.
inline double weight_growth(const Weigher &weigher, const ViewBounds::Since &d, double nearest,
                            bool cone) {
    if (!(d.moved < nearest))
        return INFINITY;
    const double x = d.moved / nearest;
    return cone ? 1.0 + x : (1.0 + x) * std::exp((d.turn + std::asin(x)) / weigher.falloff());
}

// The logarithms of that factor and of the one by which such a weight may have shrunk
// ((1 - x) * exp(-(turn + asin x) / falloff) with x = moved / nearest, since the distance then was
// at least nearest - moved; `cone`: the node is inside the view cone now, so only the distance's
// share), over-estimated without transcendental functions: ln(1 + x) <= x, -ln(1 - x) <=
// x / (1 - x) and asin x <= x / sqrt(1 - x²). For the per-node tests an update makes for every
// live node it visits.
inline double log_growth(const Weigher &weigher, const ViewBounds::Since &d, double nearest,
                         bool cone) {
    if (!(d.moved < nearest))
        return INFINITY;
    const double x = d.moved / nearest;
    return cone ? x : x + (d.turn + x / std::sqrt(1.0 - x * x)) / weigher.falloff();
}

inline double log_shrink(const Weigher &weigher, const ViewBounds::Since &d, double nearest,
                         bool cone) {
    if (!(d.moved < nearest))
        return INFINITY;
    const double x = d.moved / nearest;
    const double angle = cone ? 0.0 : (d.turn + x / std::sqrt(1.0 - x * x)) / weigher.falloff();
    return x / (1.0 - x) + angle;
}

// The same bounds linear in x for x <= 1/4, where x / (1 - x) <= 4/3 x and asin x <= x / sqrt(1 -
// x²) <= 1.0328 x: growth <= x (in the cone) or (1 + 1.0328 / falloff) x + a / falloff, shrink <=
// 4/3 x (in the cone) or (4/3 + 1.0328 / falloff) x + a / falloff. Whether a bound of logarithmic
// margin `slack` (after the turn's share a / falloff) holds for nodes within r of p, the eye having
// moved by `moved`, with `per_x` the factor of x: slack > per_x x, with x <= 1/4, tested without a
// division or a square root, as the update's walk over the live nodes pays it for every node
// (docs/decisions/007-seen-bounds.md).
inline constexpr double k_asin_quarter = 1.0329; // > 1 / sqrt(1 - 1/16)
inline bool moved_within(const glm::dvec3 &eye, const glm::dvec3 &p, double r, double moved,
                         double slack, double per_x) {
    if (!(slack > 0.0))
        return false;
    const glm::dvec3 d = p - eye;
    const double d2 = glm::dot(d, d);
    const double quarter = r + 4.0 * moved; // x <= 1/4: |p - eye| - r >= 4 moved
    if (!(d2 >= quarter * quarter))
        return false;
    // slack (|p - eye| - r) > per_x moved, squared: both sides are positive.
    const double rhs = slack * r + per_x * moved * (1.0 + 1e-9);
    return slack * slack * d2 > rhs * rhs * (1.0 + 1e-9);
}

// Live node l's seen bound (FanBounds::seen_log) carried to the current view, as a logarithm
// (+inf: none that carries over).
inline double seen_now(const EraserState &s, const FrameState &frame, const FanBounds &l) {
    if (!(l.seen_log < INFINITY))
        return INFINITY;
    if (std::uint32_t(l.seen_at) == frame.seen.updates)
        return double(l.seen_log);
    const ViewBounds::Since *d = since(s, frame, l.seen_at);
    if (!d)
        return INFINITY;
    const double nearest = glm::length(to_glm(l.p) - s.weights.view.eye) - double(l.reach);
    return double(l.seen_log) + log_growth(s.weights.weigher, *d, nearest, l.seen_cone);
}

// Before an update's erase of h.v: its ring nodes' seen bounds carried to this view (+inf: none),
// for carry_seen.
inline void seen_before(const EraserState &s, const FrameState &frame, const Hole &h,
                        std::array<double, k_max_ring> &old) {
    const bool kept = !frame.fans_stale && keeps_bounds(s, frame);
    for (int i = 0; i < h.n; ++i)
        old[std::size_t(i)] =
            kept ? seen_now(s, frame, frame.fans[live_slot(s, node_of(s, h.r[i]))]) : INFINITY;
}

// After it: each ring node gets back a seen bound, which widen_fans dropped, made under this view:
// its faces the erase left as they were are within their old bound (`old`), and the new ones
// within the erase's cost, the exact largest weighted deviation of the samples in the hole. Else
// the next update walked their fans again (docs/decisions/007-seen-bounds.md).
inline void carry_seen(const EraserState &s, FrameState &frame, const Hole &h,
                       const std::array<double, k_max_ring> &old) {
    const double cost = h.sp > 0.0 ? std::log(h.sp * (1.0 + 1e-6)) : -INFINITY;
    for (int i = 0; i < h.n; ++i) {
        if (!(old[std::size_t(i)] < INFINITY))
            continue;
        FanBounds &l = frame.fans[live_slot(s, node_of(s, h.r[i]))];
        const glm::dvec3 p = to_glm(l.p), r(double(l.reach));
        l.seen_log = float_up(std::max(old[std::size_t(i)], cost) + 1e-6);
        l.seen_at = frame.seen.updates;
        l.seen_cone = s.weights.weigher.in_cone(p - r, p + r);
    }
}

// The bound face f's seen bound gives under the current view for nodes in the box [lo, hi] (its
// swallowed nodes' box), or infinity when it has none that carries over.
double seen_bound(const EraserState &s, const FrameState &frame, FH f, const glm::dvec3 &lo,
                  const glm::dvec3 &hi);

// Face f's swallowed nodes, in the box [lo, hi], have weighted deviations <= seen under the
// current view: kept for the updates that follow (see ViewBounds::face_seen_dev).
void remember_seen(ViewBounds &bounds, const Weigher &weigher, FH f, double seen,
                   const glm::dvec3 &lo, const glm::dvec3 &hi);

} // namespace tinlod::refine
