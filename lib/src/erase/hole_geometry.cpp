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

} // namespace tinlod::erase
