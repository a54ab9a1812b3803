// A live node's bounds on its fan's swallowed nodes (FanBounds::reach, fan_dev and the seen
// bound), which let an update clear a fan without walking it, and the walk that seeds the recover
// worklist with the faces they cannot clear.
#pragma once

#include "erase/erase_cost.hpp"
#include "erase/state.hpp"
#include "refine/motion_bounds.hpp"

#include <vector>

namespace tinlod::refine {

// A bound on the weighted deviation of the swallowed nodes of live node l's fan under the current
// view, from its bounds alone: the largest deviation times the largest weight in the cube they lie
// in.
inline double fan_bound(const Weigher &weigher, const FanBounds &l) {
    if (l.fan_dev <= 0.0f)
        return 0.0;
    const glm::dvec3 p = to_glm(l.p);
    const glm::dvec3 r(double(l.reach));
    return double(l.fan_dev) * weigher.bound(p - r, p + r) * k_rounded_weight;
}

// A bound on the weighted deviation of live face f's swallowed nodes under the current view: the
// smaller of its seen bound carried over and their largest deviation times the largest weight in
// the box they lie in, without visiting them (0 when it swallowed none).
double face_bound(const EraserState &s, const FrameState &frame, FH f);

// The nodes swallowed by the faces live node l seeds have weighted deviations <= bound under the
// current view.
inline void remember_fan(const EraserState &s, const FrameState &frame, FanBounds &l,
                         double bound) {
    if (keeps_bounds(s, frame)) {
        const glm::dvec3 p = to_glm(l.p), r(double(l.reach));
        l.seen_log = float_up(std::log(bound) + 1e-6);
        l.seen_at = frame.seen.updates;
        l.seen_cone = s.weights.weigher.in_cone(p - r, p + r);
    }
}

// Whether the nodes swallowed by the faces live node l seeds cost at most `recover_above` by the
// node's own bounds: its seen bound carried over, then its fan's box (remembered when it clears
// them).
inline bool fan_cleared(const EraserState &s, const FrameState &frame, FanBounds &l,
                        double recover_above, double log_recover) {
    if (l.seen_log < INFINITY) {
        if (const ViewBounds::Since *d = since(s, frame, l.seen_at)) {
            const double falloff = s.weights.weigher.falloff();
            if (moved_within(s.weights.view.eye, to_glm(l.p), double(l.reach), d->moved,
                             log_recover - double(l.seen_log) -
                                 (l.seen_cone ? 0.0 : d->turn / falloff),
                             l.seen_cone ? 1.0 : 1.0 + k_asin_quarter / falloff))
                return true;
            if (seen_now(s, frame, l) <= log_recover)
                return true;
        }
    }
    const double box = fan_bound(s.weights.weigher, l);
    if (!(box > recover_above)) {
        remember_fan(s, frame, l, box);
        return true;
    }
    return false;
}

// The fan bounds of every live node and cell, from the fans as they stand (see
// FrameState::fans_stale).
void rebuild_fans(const EraserState &s, FrameState &frame);

// Seeds the recover worklist with the faces of live node l's fan whose swallowed nodes may cost
// more than `recover_above` (l's own bounds did not clear them): tightens l's bounds from its fan
// as it stands unless they are that already (FanBounds::fan_exact), which may clear them, else
// tries each face's. Each face is seeded by the node its halfedge leaves from, so once, and l's
// seen bound need only cover the faces it seeds: a face near the bound makes one node walk its fan
// each update, not three.
void seed_fan(const EraserState &s, FrameState &frame, std::uint32_t slot, double recover_above,
              std::vector<FH> &work);

} // namespace tinlod::refine
