// tinlod::om::ModDistanceDecayT: the paper's distance decay as a module of OpenMesh's own
// decimation framework (DecimaterT, McDecimaterT, MixedDecimaterT). A half-edge collapse v0 -> v1
// is scored by the significance of the vertex it removes (significance.hpp, screen model):
//
//   SP = delta * k / OD * peripheral(OA),
//   delta = distance from p0 to the nearest triangle of the surface after the collapse (v0's fan
//           with v0 moved onto v1), OD = |p0 - eye|, OA = angle to the observation axis.
//
// Non-binary (the default): the priority is SP, and collapses with SP >= tolerance are illegal.
// Binary (set_binary(true)): a veto beside a priority module such as ModQuadricT: LEGAL_COLLAPSE
// while SP < tolerance, ILLEGAL_COLLAPSE otherwise. It composes with ModNormalFlippingT and
// ModAspectRatioT like any stock module. The module owns no mesh property.
#pragma once

#include "tinlod/significance.hpp"
#include "tinlod/view.hpp"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace tinlod::om {

namespace detail {

template <class Point> glm::dvec3 to_glm(const Point &p) { return {p[0], p[1], p[2]}; }

// Distance from p to the triangle abc (closest point by regions, Ericson, Real-Time Collision
// Detection, 5.1.5).
inline double point_triangle_distance(const glm::dvec3 &p, const glm::dvec3 &a, const glm::dvec3 &b,
                                      const glm::dvec3 &c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0)
        return glm::length(p - a);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3)
        return glm::length(p - b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
        return glm::length(p - (a + ab * (d1 / (d1 - d3))));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6)
        return glm::length(p - c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
        return glm::length(p - (a + ac * (d2 / (d2 - d6))));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const double denom = 1.0 / (va + vb + vc);
    return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

} // namespace detail

template <class MeshT> class ModDistanceDecayT : public OpenMesh::Decimater::ModBaseT<MeshT> {
  public:
    DECIMATING_MODULE(ModDistanceDecayT, MeshT, DistanceDecay);

    explicit ModDistanceDecayT(MeshT &mesh) : Base(mesh, false) {}

    // The observer; without one every collapse is illegal.
    void set_view(const tinlod::View &view) {
        view_ = view;
        has_view_ = true;
    }
    // tau, pixels: collapses whose SP reaches it are illegal.
    void set_tolerance(double px) { tolerance_ = px; }
    double tolerance() const { return tolerance_; }
    // Peripheral-factor parameters (the model is always screen).
    void set_significance(const tinlod::SignificanceOptions &options) { options_ = options; }

    // SP of removing v0 by the collapse: see the file comment.
    double significance(const CollapseInfo &ci) {
        if (!has_view_)
            return INFINITY;
        Mesh &m = Base::mesh();
        const glm::dvec3 p0 = detail::to_glm(ci.p0), p1 = detail::to_glm(ci.p1);
        double delta = INFINITY;
        for (auto fh : m.vf_range(ci.v0)) {
            glm::dvec3 corner[3];
            int i = 0;
            bool touches_v1 = false;
            for (auto vh : m.fv_range(fh)) {
                touches_v1 |= vh == ci.v1;
                corner[i++] = vh == ci.v0 ? p1 : detail::to_glm(m.point(vh));
            }
            if (touches_v1)
                continue; // collapses away with the edge
            delta = std::min(delta,
                             detail::point_triangle_distance(p0, corner[0], corner[1], corner[2]));
        }
        if (!std::isfinite(delta))
            delta = glm::length(p1 - p0); // every face touches v1: the move itself
        return delta * tinlod::screen_weight(view_, p0, options_);
    }

    float collapse_priority(const CollapseInfo &ci) override {
        const double sp = significance(ci);
        if (!(sp < tolerance_))
            return float(Base::ILLEGAL_COLLAPSE);
        return Base::is_binary() ? float(Base::LEGAL_COLLAPSE) : float(sp);
    }

  private:
    tinlod::View view_;
    bool has_view_ = false;
    double tolerance_ = 1.0;
    tinlod::SignificanceOptions options_;
};

} // namespace tinlod::om
