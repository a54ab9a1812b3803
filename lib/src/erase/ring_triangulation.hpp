// Paper steps 3-4: the hole a node leaves, re-triangulated in its projection plane by ear
// clipping, with the paper's erasing-ability test of an ear. The ring (paper step 3) is the node's
// spokes in the order the half-edges circulate, counter-clockwise (gather_ring, hole_geometry.hpp).
// clip_ears is what the erase runs; ring_orientation, is_erasable_ear and triangulate_ring give
// the tests and the benchmarks the same ears on a polygon.
#pragma once

#include "tinlod/decimate.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace tinlod::erase {

// One triangle of a re-triangulated ring: three ring indices, counter-clockwise.
struct RingTriangle {
    std::uint8_t a, b, c;
};

enum class RingOrientation { ccw, cw, degenerate };

// Orientation of the closed polygon `ring` by the sign of its area.
RingOrientation ring_orientation(std::span<const glm::dvec2> ring);

// The paper's erasing-ability test for the ear at ring index i of the counter-clockwise polygon
// `ring`: the corner (i-1, i, i+1) is strictly convex and no other ring node lies in the closed
// triangle.
bool is_erasable_ear(std::span<const glm::dvec2> ring, int i);

// Ear clipping of a simple counter-clockwise polygon (at most k_max_ring nodes), as clip_ears.
// Returns ring.size() - 2 triangles, or an empty vector when the ring cannot be triangulated
// without a fold-over.
std::vector<RingTriangle> triangulate_ring(std::span<const glm::dvec2> ring);

// Twice the signed area of the triangle abc: positive when it is counter-clockwise.
inline double orient(const glm::dvec2 &a, const glm::dvec2 &b, const glm::dvec2 &c) {
    return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

// Ear clipping of the counter-clockwise polygon q[0..n); writes n-2 triangles to `out` and returns
// their count, or -1 when no erasable ear is left before the end. Each step clips the best shaped
// Delaunay ear, or the best shaped ear when none is Delaunay; the circumcircle test runs only on
// ears in order of quality until one passes (a Delaunay ear stays Delaunay as nodes leave).
int clip_ears(const glm::dvec2 *q, int n, RingTriangle *out);

} // namespace tinlod::erase
