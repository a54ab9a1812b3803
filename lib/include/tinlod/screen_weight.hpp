// The screen weight of a deviation seen from one view, k / OD * peripheral(OA) (the formula in
// significance.hpp), with bounds over boxes: the one definition used by significance.hpp's
// screen_weight and peripheral_factor, the node erase (lib/src/erase), the refiner and the
// quad-tree retrieval when it bounds the same weighted error (RetrieveOptions::peripheral).
#pragma once

#include "tinlod/significance.hpp"
#include "tinlod/view.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace tinlod {

// Pixels per unit of deviation at a point for one view: k / OD * peripheral(OA), with the view's
// frame computed once; 1 without a view or in the vertical model.
class Weigher {
  public:
    Weigher() = default;
    Weigher(const View *view, const SignificanceOptions &options) {
        if (view && options.model != SpModel::vertical)
            *this = Weigher(*view, options);
    }
    // The screen model's weight for this view, whatever options.model says.
    Weigher(const View &view, const SignificanceOptions &options) {
        unit_ = false;
        eye_ = view.eye;
        const View::Frame frame = view.frame();
        f_ = frame.forward;
        r_ = frame.right;
        u_ = frame.up;
        k_ = view.k();
        half_w_ = view.viewport_w / 2.0 + options.cone_margin_px;
        half_h_ = view.viewport_h / 2.0 + options.cone_margin_px;
        cone_ = std::atan(0.5 * std::hypot(double(view.viewport_w), double(view.viewport_h)) / k_);
        cos_cone_ = std::cos(cone_);
        sin_cone_ = std::sin(cone_);
        // The cone through the corners of the frustum widened by the margin: the factor is 1 in
        // that frustum, so up to this angle.
        cone_margin_ = std::atan(std::hypot(half_w_, half_h_) / k_);
        cos_cone_margin_ = std::cos(cone_margin_);
        sin_cone_margin_ = std::sin(cone_margin_);
        falloff_ = std::max(options.falloff_deg, 1e-6) * M_PI / 180.0;
        floor_ = options.floor;
        // Beyond this cosine of the angle to the axis the factor is the floor (a hair inside, so
        // rounding never takes the shortcut where the formula is above the floor).
        const double floored = cone_ + falloff_ * std::log(1.0 / std::max(floor_, 1e-300));
        floor_cos_ = floored < M_PI ? std::cos(floored) - 1e-9 : -2.0;
        if (floored < M_PI) {
            cos_floored_ = std::cos(floored);
            sin_floored_ = std::sin(floored);
        }
    }
    // The weight at p; infinite at the eye.
    double operator()(const glm::dvec3 &p) const {
        if (unit_)
            return 1.0;
        const glm::dvec3 d = p - eye_;
        const double od = glm::length(d);
        if (!(od > 0.0))
            return INFINITY;
        return k_ / od * peripheral(d, od);
    }
    // peripheral(OA) at p, in [floor, 1]: 1 inside the margin-widened frustum and the view cone
    // (and at the eye).
    double peripheral(const glm::dvec3 &p) const {
        if (unit_)
            return 1.0;
        const glm::dvec3 d = p - eye_;
        const double od = glm::length(d);
        return od > 0.0 ? peripheral(d, od) : 1.0;
    }
    // An upper bound of the weight at p without the peripheral factor's transcendental functions:
    // k / OD (the factor is at most 1).
    double upper(const glm::dvec3 &p) const {
        if (unit_)
            return 1.0;
        return k_ / glm::length(p - eye_);
    }
    // An upper bound of the weight anywhere in the box [lo, hi]: k over the box's distance to the
    // eye, times the peripheral factor of the smallest angle its bounding sphere makes with the
    // axis (1 up to the cone through the margin-widened frustum's corners, all of whose points
    // have that factor).
    double bound(const glm::dvec3 &lo, const glm::dvec3 &hi) const {
        if (unit_)
            return 1.0;
        const double dist = glm::length(glm::clamp(eye_, lo, hi) - eye_);
        if (!(dist > 0.0))
            return INFINITY;
        const glm::dvec3 c = 0.5 * (lo + hi) - eye_;
        const double dc = glm::length(c), radius = 0.5 * glm::length(hi - lo);
        if (dc <= radius)
            return k_ / dist;
        // Inside that cone widened by the sphere's half angle asin(rho), tested by cosines (cone +
        // asin(rho) <= pi, where the cosine falls): the factor is 1, which bounds any angle.
        const double rho = radius / dc, cos_axis = glm::dot(c, f_) / dc;
        const double cos_rho = std::sqrt(1.0 - rho * rho);
        if (cos_axis >= cos_cone_margin_ * cos_rho - sin_cone_margin_ * rho)
            return k_ / dist;
        // Beyond the angle where the factor reaches the floor even at the sphere's nearest point:
        // the angle to its centre exceeds that one plus asin(rho) (a sum under pi, as rho is under
        // its sine), tested by cosines with a hair of margin.
        if (rho < sin_floored_ && cos_axis < cos_floored_ * cos_rho - sin_floored_ * rho - 1e-9)
            return k_ / dist * floor_;
        const double angle = std::acos(std::clamp(cos_axis, -1.0, 1.0)) - std::asin(rho);
        if (angle <= cone_margin_)
            return k_ / dist;
        return k_ / dist * std::max(floor_, std::exp(-(angle - cone_) / falloff_));
    }

    // Whether the box [lo, hi] lies inside the view cone, where the peripheral factor is 1: the
    // angle to the axis of its bounding sphere's centre is at most the cone's less the sphere's
    // half angle, asin(rho), tested by cosines (cone < pi / 2).
    bool in_cone(const glm::dvec3 &lo, const glm::dvec3 &hi) const {
        if (unit_)
            return true;
        const glm::dvec3 c = 0.5 * (lo + hi) - eye_;
        return sphere_in_cone(c, glm::length(c), 0.5 * glm::length(hi - lo));
    }

    // A lower bound of the weight anywhere in the box [lo, hi]: k over the distance to its farthest
    // corner, times the peripheral factor of the largest angle its bounding sphere makes with the
    // axis (the factor falls with the angle).
    double lower(const glm::dvec3 &lo, const glm::dvec3 &hi) const {
        if (unit_)
            return 1.0;
        const double dist = glm::length(glm::max(glm::abs(lo - eye_), glm::abs(hi - eye_)));
        const glm::dvec3 c = 0.5 * (lo + hi) - eye_;
        const double dc = glm::length(c), radius = 0.5 * glm::length(hi - lo);
        if (sphere_in_cone(c, dc, radius))
            return k_ / dist; // the factor is 1 at every angle the sphere makes
        if (glm::dot(c, f_) < floor_cos_ * dc)
            return k_ / dist * floor_; // its centre, and so its farthest angle, is floored
        const double angle = dc <= radius ? M_PI
                                          : std::acos(std::clamp(glm::dot(c, f_) / dc, -1.0, 1.0)) +
                                                std::asin(radius / dc);
        const double beyond = angle - cone_;
        return beyond <= 0.0 ? k_ / dist
                             : k_ / dist * std::max(floor_, std::exp(-beyond / falloff_));
    }

    double falloff() const { return falloff_; } // the peripheral factor's e-folding, radians

  private:
    // peripheral(OA) at eye + d, |d| = od > 0.
    double peripheral(const glm::dvec3 &d, double od) const {
        const double depth = glm::dot(d, f_);
        if (depth > 0.0 && std::abs(glm::dot(d, r_)) * k_ <= half_w_ * depth &&
            std::abs(glm::dot(d, u_)) * k_ <= half_h_ * depth)
            return 1.0; // inside the frustum
        if (depth >= cos_cone_ * od)
            return 1.0; // inside the view cone
        if (depth < floor_cos_ * od)
            return floor_; // far outside the view cone: no arc cosine
        const double beyond = std::acos(std::clamp(depth / od, -1.0, 1.0)) - cone_;
        return beyond <= 0.0 ? 1.0 : std::max(floor_, std::exp(-beyond / falloff_));
    }

    // in_cone for the sphere of centre eye + c (at distance dc) and the given radius.
    bool sphere_in_cone(const glm::dvec3 &c, double dc, double radius) const {
        const double rho = radius / dc;
        if (!(rho < sin_cone_))
            return false;
        const double cos_limit = cos_cone_ * std::sqrt(1.0 - rho * rho) + sin_cone_ * rho;
        return glm::dot(c, f_) >= dc * cos_limit * (1.0 + 1e-9);
    }

    bool unit_ = true;
    glm::dvec3 eye_{0.0}, f_{0.0}, r_{0.0}, u_{0.0};
    double k_ = 1.0, half_w_ = 0.0, half_h_ = 0.0, cone_ = 0.0, falloff_ = 1.0, floor_ = 0.0;
    double floor_cos_ = -2.0;
    double cos_floored_ = -1.0, sin_floored_ = 0.0; // of the angle where the factor is floored
    double cos_cone_ = 1.0, sin_cone_ = 0.0;
    double cone_margin_ = 0.0, cos_cone_margin_ = 1.0, sin_cone_margin_ = 0.0;
};

} // namespace tinlod
