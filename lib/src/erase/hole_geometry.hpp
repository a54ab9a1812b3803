// The geometry of the hole a node leaves: its ring, the projection plane, the new triangles' affine
// frames (their planes: triangle_plane.hpp), and a node's deviation from them (node_deviation:
// vertical on a TIN, the distance to the triangle on a surface mesh).
#pragma once

#include "erase/ring_triangulation.hpp"
#include "float_rounding.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/tin.hpp"
#include "triangle_plane.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tinlod::erase {

using VH = Mesh::VertexHandle;
using HH = Mesh::HalfedgeHandle;
using EH = Mesh::EdgeHandle;
using FH = Mesh::FaceHandle;

inline glm::dvec3 to_glm(const Mesh::Point &p) { return {p[0], p[1], p[2]}; }

using tinlod::float_down; // float_rounding.hpp, named here for the erase and the refiner
using tinlod::float_up;
using tinlod::rounding_margin;

// A new triangle's barycentric weights as affine functions of the projected point, and its plane
// (xy only).
struct TriangleFrame {
    PlaneWeights w;
    TrianglePlane plane;
};

// The hole a node leaves, projected and re-triangulated (scratch of one evaluation).
struct Hole {
    VH v;
    int n = 0; // ring nodes
    bool boundary = false;
    std::array<VH, k_max_ring> r;
    std::array<HH, k_max_ring> h; // spokes v -> r_i
    std::array<glm::dvec3, k_max_ring> p;
    std::array<glm::dvec2, k_max_ring> q; // projected ring
    std::array<RingTriangle, k_max_ring> tri;
    std::array<TriangleFrame, k_max_ring> frame;
    int ntri = 0;
    glm::dvec3 origin{0.0}, ex{1, 0, 0}, ey{0, 1, 0}; // projection frame (xy: the world frame)
    double delta = 0.0; // the node's own deviation from the new triangles
    double sp =
        0.0; // the SP of the erase: max weighted deviation of the nodes the new faces swallow
    std::uint32_t star = 0; // the node that gave the SP, and its (unweighted) deviation
    double star_dev = 0.0;
    bool deferred = false; // the fan swallowed more nodes than the evaluation may visit
    // A grid TIN's evaluation (see scan_lattice): per new triangle, the largest deviation of the
    // samples it swallows and the sample that has it (-1 when none deviates).
    std::array<float, k_max_ring> tri_maxdev;
    std::array<std::int32_t, k_max_ring> tri_worst;
    // A band's samples whose weighted deviation may raise the SP (see scan_hole), in scan order:
    // the sample, its deviation, that times the band's weight bound, and its weighted deviation
    // (-1 until computed).
    struct Pending {
        std::uint32_t node;
        double dev, upper, weighted;
    };
    std::vector<Pending> pending;
    std::vector<std::uint32_t> pending_order;
};

inline glm::dvec2 project(const Hole &h, const glm::dvec3 &p) {
    const glm::dvec3 d = p - h.origin;
    return {glm::dot(d, h.ex), glm::dot(d, h.ey)};
}

// The frame of the triangle with projected corners qa, qb, qc; `xy`: its heights za, zb, zc too.
inline TriangleFrame triangle_frame(const glm::dvec2 &qa, const glm::dvec2 &qb,
                                    const glm::dvec2 &qc, bool xy, double za = 0.0, double zb = 0.0,
                                    double zc = 0.0) {
    TriangleFrame f;
    f.w = plane_weights(qa, qb, qc);
    if (xy)
        f.plane = TrianglePlane(f.w, za, zb, zc);
    return f;
}

// Fills the affine frames of the hole's new triangles.
void frame_triangles(Hole &h, bool xy);

// The new triangle covering p (the one where p's smallest weight is largest), and p's deviation
// from it (node_deviation). `inside`, if given, tells whether that triangle covers p (projected,
// edges included) or is only the nearest.
inline std::uint8_t locate(const Hole &h, bool xy, const glm::dvec3 &p, double &dev,
                           bool *inside = nullptr) {
    const glm::dvec2 x2 = project(h, p);
    const glm::dvec3 x(x2.x, x2.y, 1.0);
    int best = 0;
    double best_min = -INFINITY;
    for (int t = 0; t < h.ntri; ++t) {
        const double b0 = glm::dot(h.frame[t].w.a, x), b1 = glm::dot(h.frame[t].w.b, x);
        const double lowest = std::min({b0, b1, 1.0 - b0 - b1});
        if (lowest > best_min) {
            best_min = lowest;
            best = t;
        }
        if (lowest >= 0.0)
            break; // inside (or on the edge of) this triangle
    }
    if (inside)
        *inside = best_min >= 0.0;
    const RingTriangle &t = h.tri[best];
    dev = node_deviation(xy, h.frame[best].plane, p, h.p[t.a], h.p[t.b], h.p[t.c]);
    return std::uint8_t(best);
}

inline HH find_halfedge(const Mesh &m, VH a, VH b) {
    const HH start = m.halfedge_handle(a);
    if (!start.is_valid())
        return HH();
    HH he = start;
    for (int guard = 0; guard < 4 * k_max_ring; ++guard) {
        if (m.to_vertex_handle(he) == b)
            return he;
        he = m.next_halfedge_handle(m.opposite_halfedge_handle(he));
        if (he == start)
            break;
    }
    return HH();
}

// Spokes of v counter-clockwise; false for an isolated, complex or too-high-valence node.
inline bool gather_ring(const Mesh &m, VH v, Hole &h, int max_valence) {
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
