// Paper steps 3-4: the hole a node leaves, re-triangulated in its projection plane by ear
// clipping, with the paper's erasing-ability test of an ear. The public ring functions of
// decimate.hpp (ring_orientation, order_ring, is_erasable_ear, triangulate_ring) are defined in
// ring_triangulation.cpp on the same ears.
#pragma once

#include "tinlod/decimate.hpp"

#include <glm/glm.hpp>

namespace tinlod::erase {

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
