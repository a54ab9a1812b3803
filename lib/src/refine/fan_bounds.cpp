// Fan bounds (fan_bounds.hpp).
#include "refine/fan_bounds.hpp"

#include "erase/swallowed.hpp"

#include <algorithm>
#include <cmath>

namespace tinlod::refine {

using namespace erase;

double face_bound(const EraserState &s, const FrameState &frame, FH f) {
    const Mesh &m = *s.input.mesh;
    if (s.faces.face_head[f.idx()] < 0 || s.faces.face_maxdev[f.idx()] <= 0.0f)
        return 0.0;
    const HH he = m.halfedge_handle(f);
    const auto [lo, hi] =
        swallowed_box(s.faces, s.input.xy, f, to_glm(m.point(m.from_vertex_handle(he))),
                      to_glm(m.point(m.to_vertex_handle(he))),
                      to_glm(m.point(m.to_vertex_handle(m.next_halfedge_handle(he)))));
    return std::min(double(s.faces.face_maxdev[f.idx()]) * s.weights.weigher.bound(lo, hi) *
                        k_rounded_weight,
                    seen_bound(s, frame, f, lo, hi));
}

namespace {

// Sets live node l's fan bounds from its fan as it stands: the largest deviation of its faces'
// swallowed nodes, and their reach (the farthest corner, plus that deviation).
static void fan_extent(const EraserState &s, VH v, FanBounds &l) {
    const Mesh &m = *s.input.mesh;
    const glm::dvec3 px = to_glm(l.p);
    double far2 = 0.0;
    float fan_dev = 0.0f;
    for (auto he : m.voh_range(v)) {
        const glm::dvec3 d = to_glm(m.point(m.to_vertex_handle(he))) - px;
        far2 = std::max(far2, glm::dot(d, d));
        const FH f = m.face_handle(he);
        if (f.is_valid())
            fan_dev = std::max(fan_dev, s.faces.face_maxdev[f.idx()]);
    }
    l.reach = float_up(std::sqrt(far2) + double(fan_dev));
    l.fan_dev = fan_dev;
    l.fan_exact = true;
}

} // namespace

void rebuild_fans(const EraserState &s, FrameState &frame) {
    for (Cell &cell : frame.grid.cells) {
        cell.fan_dev = 0.0f;
        cell.reach = 0.0f;
    }
    for (std::size_t i = 0; i < s.live.list.size(); ++i) {
        FanBounds &l = frame.fans[i];
        fan_extent(s, VH(s.live.list[i].vertex), l);
        l.seen_log = INFINITY;
        Cell &cell = frame.grid.cells[l.cell];
        cell.fan_dev = std::max(cell.fan_dev, l.fan_dev);
        cell.reach = std::max(cell.reach, l.reach);
    }
    frame.fans_stale = false;
}

void seed_fan(const EraserState &s, FrameState &frame, std::uint32_t slot, double recover_above,
              std::vector<FH> &work) {
    const Mesh &m = *s.input.mesh;
    const VH x(s.live.list[slot].vertex);
    FanBounds &l = frame.fans[slot];
    if (!l.fan_exact)
        fan_extent(s, x, l); // else its bounds are what the walk would give
    const double box = fan_bound(s.weights.weigher, l);
    if (!(box > recover_above)) {
        remember_fan(s, frame, l, box);
        return;
    }
    double most = 0.0;
    for (auto he : m.voh_range(x)) {
        const FH f = m.face_handle(he);
        if (!f.is_valid() || m.halfedge_handle(f) != he)
            continue; // another corner's to seed
        const double bound = face_bound(s, frame, f);
        most = std::max(most, bound);
        if (bound > recover_above)
            work.push_back(f);
    }
    remember_fan(s, frame, l, most);
}

} // namespace tinlod::refine
