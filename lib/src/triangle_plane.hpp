// A TIN triangle's plane over xy, the one definition every scan, bound and measure of a TIN's
// triangles evaluates: the height at (x, y), the slope, and a point's vertical deviation widened by
// the float-rounding margin (float_rounding.hpp); and a node's deviation from a triangle, vertical
// on a TIN, the distance to the triangle on a surface mesh.
#pragma once

#include "float_rounding.hpp"
#include "tinlod/closest_point.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace tinlod {

// The barycentric weights of a triangle's corners a and b as affine functions of the point:
// dot(a, (x, y, 1)); corner c gets the rest.
struct PlaneWeights {
    glm::dvec3 a, b;
};

// The weights of the triangle with corners qa, qb, qc (not collinear).
inline PlaneWeights plane_weights(const glm::dvec2 &qa, const glm::dvec2 &qb,
                                  const glm::dvec2 &qc) {
    // One over twice the signed area (ring_triangulation's orient(qa, qb, qc)); then the weights
    // are orient(qb, qc, x) and orient(qc, qa, x) over it.
    const double inv = 1.0 / ((qb.x - qa.x) * (qc.y - qa.y) - (qc.x - qa.x) * (qb.y - qa.y));
    return {glm::dvec3(qb.y - qc.y, qc.x - qb.x, qb.x * qc.y - qc.x * qb.y) * inv,
            glm::dvec3(qc.y - qa.y, qa.x - qc.x, qc.x * qa.y - qa.x * qc.y) * inv};
}

class TrianglePlane {
  public:
    TrianglePlane() = default;
    // The plane through corners a, b, c (not collinear in xy).
    TrianglePlane(const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c)
        : TrianglePlane(plane_weights(glm::dvec2(a), glm::dvec2(b), glm::dvec2(c)), a.z, b.z, c.z) {
    }
    // The plane through heights za, zb, zc at the corners of weights w.
    TrianglePlane(const PlaneWeights &w, double za, double zb, double zc)
        : h_(w.a * za + w.b * zb + (glm::dvec3(0.0, 0.0, 1.0) - w.a - w.b) * zc),
          slope_(std::sqrt(h_.x * h_.x + h_.y * h_.y)) {}

    double height(double x, double y) const { return h_.x * x + h_.y * y + h_.z; }
    double slope() const { return slope_; } // |grad z|

    // What float corners can move the plane at a point whose largest coordinate magnitude is
    // `coord` (rounding_margin).
    double margin(double coord) const { return rounding_margin(coord, slope_); }
    // The margin at the corner of a, b, c farthest from the axes: it holds at every point of the
    // triangle, so a scan of the triangle's points takes it once.
    double margin_over(const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c) const {
        return margin(std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y),
                                std::abs(c.x), std::abs(c.y)}));
    }

    // Point p's vertical deviation from the plane.
    double vertical(double x, double y, double z) const { return std::abs(z - height(x, y)); }
    double vertical(const glm::dvec3 &p) const { return vertical(p.x, p.y, p.z); }
    // That widened by `margin` (at least margin(its largest |x|, |y|)): it never understates the
    // deviation from the plane through the exact corners, but for this evaluation's own rounding.
    double deviation(double x, double y, double z, double margin) const {
        return vertical(x, y, z) + margin;
    }
    double deviation(const glm::dvec3 &p) const {
        return deviation(p.x, p.y, p.z, margin(std::max(std::abs(p.x), std::abs(p.y))));
    }

    // The second evaluation, of the lattice scans outside the erase (greedy insertion, the
    // quad-tree's bounds): the gradient from corner a, a row at a time, z = start(y) + gx x with
    // start(y) = za + gy (y - ya) - gx xa: one multiply-add per sample. It rounds differently
    // from height(), and their chosen samples and bounds were made with it.
    struct Rows {
        double gx, gy, xa, ya, za;
        double start(double y) const { return za + gy * (y - ya) - gx * xa; }
        // |z - the plane's height at x| on the row of `start`.
        double deviation(double start, double x, double z) const {
            return std::abs(z - (start + gx * x));
        }
    };
    static Rows rows(const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c) {
        const double dx1 = b.x - a.x, dy1 = b.y - a.y, dz1 = b.z - a.z;
        const double dx2 = c.x - a.x, dy2 = c.y - a.y, dz2 = c.z - a.z;
        const double det = dx1 * dy2 - dy1 * dx2;
        return {(dz1 * dy2 - dz2 * dy1) / det, (dx1 * dz2 - dx2 * dz1) / det, a.x, a.y, a.z};
    }

    // The third evaluation, of the measured error (metrics.cpp): from a point's weights times
    // `area` (its edge functions, which the coverage test computes). It keeps the reported errors
    // to their last digits, where height()'s constant term loses about 10^-12 over a large grid.
    static double interpolate(double wa, double wb, double wc, double za, double zb, double zc,
                              double area) {
        return (wa * za + wb * zb + wc * zc) / area;
    }

  private:
    glm::dvec3 h_{0.0}; // z = dot(h_, (x, y, 1))
    double slope_ = 0.0;
};

// A node at p's deviation from the triangle with corners a, b, c (plane: its plane): on a TIN
// (`xy`) its widened vertical deviation, on a surface mesh its distance to the triangle (a bound
// of its distance to the surface; the distance to the triangle's plane is not, where the triangle
// is steep in the projection plane).
inline double node_deviation(bool xy, const TrianglePlane &plane, const glm::dvec3 &p,
                             const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c) {
    return xy ? plane.deviation(p) : triangle_distance(p, a, b, c);
}

} // namespace tinlod
