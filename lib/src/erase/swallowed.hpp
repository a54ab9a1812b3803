// The swallowed lists: every erased node stays filed under the face that covers it (in the
// projection plane), so a face's error is that of the nodes in its list. A grid TIN keeps no lists
// (lattice_scan.hpp): only each face's worst sample, as the list's head.
#pragma once

#include "erase/state.hpp"

#include <utility>

namespace tinlod::erase {

// The fans of the live nodes among the points p[0..count) (node ids `ids`, a hole's or a face's)
// now hold the triangles tri[0..ntri) over those points, whose swallowed nodes deviate at most
// dev[t]: the follower widens its bounds on them (refine/fan_bounds.hpp).
inline void widen_fans(EraserState &s, const glm::dvec3 *p, const std::uint32_t *ids, int count,
                       const RingTriangle *tri, const float *dev, int ntri) {
    if (s.follower)
        s.follower->fans_widened(s, p, ids, count, tri, dev, ntri);
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
void unlink_swallowed(FaceIndex &faces, Follower *follower, std::int32_t f, std::uint32_t u);

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
