// The geometry of the hole a node leaves: its ring, the projection plane, the new triangles' affine
// frames, and a node's deviation from them (vertical on a TIN, the distance to the triangle on a
// surface mesh, widened for float rounding).
#pragma once

#include "erase/ring_triangulation.hpp"
#include "float_rounding.hpp"
#include "tinlod/closest_point.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/tin.hpp"

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

// A new triangle's barycentric weights and height as affine functions of the projected point.
struct TriangleFrame {
    glm::dvec3 w0, w1;  // weight of corners a and b: dot(w, (x, y, 1)); c gets the rest
    glm::dvec3 height;  // xy: z = dot(height, (x, y, 1))
    double slope = 0.0; // xy: |grad z|
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
    const double inv = 1.0 / orient(qa, qb, qc);
    TriangleFrame f;
    // w0 = orient(qb, qc, x) / area, w1 = orient(qc, qa, x) / area
    f.w0 = glm::dvec3(qb.y - qc.y, qc.x - qb.x, qb.x * qc.y - qc.x * qb.y) * inv;
    f.w1 = glm::dvec3(qc.y - qa.y, qa.x - qc.x, qc.x * qa.y - qa.x * qc.y) * inv;
    if (xy) {
        const glm::dvec3 w2 = glm::dvec3(0.0, 0.0, 1.0) - f.w0 - f.w1;
        f.height = f.w0 * za + f.w1 * zb + w2 * zc;
        f.slope = std::sqrt(f.height.x * f.height.x + f.height.y * f.height.y);
    }
    return f;
}

// Fills the affine frames of the hole's new triangles.
void frame_triangles(Hole &h, bool xy);

// A TIN point's vertical deviation from the triangle of frame f, widened by the rounding margin.
inline double vertical_dev(const TriangleFrame &f, double x, double y, double z) {
    return std::abs(z - (f.height.x * x + f.height.y * y + f.height.z)) +
           rounding_margin(std::max(std::abs(x), std::abs(y)), f.slope);
}

// vertical_dev over one triangle of a grid TIN with corners a, b, c, its rounding margin taken
// where it is largest in the triangle (at the corner farthest from the axes).
class PlaneDev {
  public:
    PlaneDev(const TriangleFrame &f, const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c)
        : h_(f.height) {
        const double far = std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y),
                                     std::abs(c.x), std::abs(c.y)});
        margin_ = rounding_margin(far, f.slope);
    }
    double operator()(const Mesh::Point &p) const {
        const double z = h_.x * double(p[0]) + h_.y * double(p[1]) + h_.z;
        return std::abs(double(p[2]) - z) + margin_;
    }

  private:
    glm::dvec3 h_;
    double margin_;
};

// The new triangle covering p (the one where p's smallest weight is largest), and p's deviation
// from it: vertical for a TIN, its distance to the triangle otherwise (a bound of its distance to
// the surface; the distance to the triangle's plane is not, where the triangle is steep in the
// projection plane). `inside`, if given, tells whether that triangle covers p (projected, edges
// included) or is only the nearest.
inline std::uint8_t locate(const Hole &h, bool xy, const glm::dvec3 &p, double &dev,
                           bool *inside = nullptr) {
    const glm::dvec2 x2 = project(h, p);
    const glm::dvec3 x(x2.x, x2.y, 1.0);
    int best = 0;
    double best_min = -INFINITY;
    for (int t = 0; t < h.ntri; ++t) {
        const double b0 = glm::dot(h.frame[t].w0, x), b1 = glm::dot(h.frame[t].w1, x);
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
    dev = xy ? vertical_dev(h.frame[best], p.x, p.y, p.z)
             : triangle_distance(p, h.p[t.a], h.p[t.b], h.p[t.c]);
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
