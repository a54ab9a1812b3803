// A hole's ring and its new triangles' frames (hole_geometry.hpp).
#include "erase/hole_geometry.hpp"

namespace tinlod::erase {

void frame_triangles(Hole &h, bool xy) {
    for (int t = 0; t < h.ntri; ++t) {
        const RingTriangle &tri = h.tri[t];
        TriangleFrame &f = h.frame[t];
        f = triangle_frame(h.q[tri.a], h.q[tri.b], h.q[tri.c], xy, h.p[tri.a].z, h.p[tri.b].z,
                           h.p[tri.c].z);
    }
}

bool gather_ring(const Mesh &m, VH v, Hole &h, int max_valence) {
    const HH start = m.halfedge_handle(v);
    if (!start.is_valid())
        return false;
    h.v = v;
    h.boundary = m.is_boundary(start);
    const HH h0 = h.boundary ? m.opposite_halfedge_handle(m.prev_halfedge_handle(start)) : start;
    const int limit = std::min(max_valence + 1, k_max_ring);
    int n = 0;
    HH he = h0;
    do {
        if (n == limit)
            return false;
        h.h[n] = he;
        h.r[n] = m.to_vertex_handle(he);
        ++n;
        if (h.boundary && m.is_boundary(he))
            break;
        he = m.opposite_halfedge_handle(m.prev_halfedge_handle(he));
    } while (he != h0);
    h.n = n;
    if (h.boundary && he != start)
        return false; // a second boundary fan: a complex vertex
    return n >= 3;
}

} // namespace tinlod::erase
