// The swallowed lists: every erased node stays filed under the face that covers it (in the
// projection plane), so a face's error is that of the nodes in its list. A grid TIN keeps no lists
// (lattice_scan.hpp): only each face's worst sample, as the list's head.
#pragma once

#include "erase/state.hpp"

#include <utility>

namespace tinlod::erase {

// The fans of the live nodes among the points p[0..count) (node ids `ids`, a hole's or a face's)
// now hold the triangles tri[0..ntri) over those points, whose swallowed nodes deviate at most
// dev[t]: widens each corner's bounds to cover its own new triangles, as fan_extent would from them
// (their farthest corner, plus their largest deviation): bounds from the whole hole made the
// updates walk fans that the node's own bounds clear (docs/decisions/006-fan-bounds.md).
inline void widen_fans(EraserState &s, const glm::dvec3 *p, const std::uint32_t *ids, int count,
                       const RingTriangle *tri, const float *dev, int ntri) {
    if (s.frame.fans_stale)
        return;
    std::array<double, k_max_ring + 1> far2;
    std::array<float, k_max_ring + 1> most;
    std::fill_n(far2.begin(), count, 0.0);
    std::fill_n(most.begin(), count, 0.0f);
    for (int t = 0; t < ntri; ++t) {
        const std::uint8_t c[3] = {tri[t].a, tri[t].b, tri[t].c};
        for (int k = 0; k < 3; ++k) {
            const std::uint8_t i = c[k];
            for (int j = 1; j < 3; ++j) {
                const glm::dvec3 d = p[c[(k + j) % 3]] - p[i];
                far2[i] = std::max(far2[i], glm::dot(d, d));
            }
            most[i] = std::max(most[i], dev[t]);
        }
    }
    for (int i = 0; i < count; ++i) {
        if (s.history.record_of[ids[i]] >= 0)
            continue;
        LiveNode &l = live_node(s, ids[i]);
        l.seen_log = INFINITY;
        l.fan_exact = false;
        l.reach = std::max(l.reach, float_up(std::sqrt(far2[i]) + double(most[i])));
        l.fan_dev = std::max(l.fan_dev, most[i]);
        Cell &cell = s.frame.grid.cells[l.cell];
        cell.reach = std::max(cell.reach, l.reach);
        cell.fan_dev = std::max(cell.fan_dev, l.fan_dev);
    }
}

// Adds node u, deviating `dev` from face f, to f's list. The list's head stays its node of largest
// deviation (the rest in no order), so evaluate can try every fan face's worst node before it walks
// the lists.
inline void push_swallowed(FaceIndex &faces, int f, std::uint32_t u, float dev) {
    const std::int32_t head = faces.face_head[f];
    faces.swallowed_by[u] = f;
    if (head < 0 || dev > faces.face_maxdev[f]) {
        faces.next_swallowed[u] = head;
        faces.face_head[f] = std::int32_t(u);
        faces.face_maxdev[f] = std::max(faces.face_maxdev[f], dev);
    } else {
        faces.next_swallowed[u] = faces.next_swallowed[head];
        faces.next_swallowed[head] = std::int32_t(u);
    }
}

// Takes node u out of face f's list (the face keeps its deviation bound, now perhaps loose).
void unlink_swallowed(FaceIndex &faces, refine::ViewBounds &seen, std::int32_t f, std::uint32_t u);

// The box face f's swallowed nodes lie in (f's corners a, b, c): within its largest deviation of it
// (with a margin for the float rounding of that deviation), a TIN's inside it in xy and vertically
// off it, a surface mesh's at that distance of it in any direction, so the box widens on every
// axis.
inline std::pair<glm::dvec3, glm::dvec3> swallowed_box(const FaceIndex &faces, bool xy, FH f,
                                                       const glm::dvec3 &a, const glm::dvec3 &b,
                                                       const glm::dvec3 &c) {
    const double dz = 1.001 * double(faces.face_maxdev[f.idx()]);
    const glm::dvec3 margin = xy ? glm::dvec3(0.0, 0.0, dz) : glm::dvec3(dz);
    return {glm::min(glm::min(a, b), c) - margin, glm::max(glm::max(a, b), c) + margin};
}

} // namespace tinlod::erase
