// The geometric concepts with one definition each (#47 item 4): float rounding and the plane's
// rounding margin (lib/src/float_rounding.hpp), the projection frame (View::frame), the screen
// weight (tinlod/screen_weight.hpp) as significance.hpp's functions give it.
#include "../lib/src/float_rounding.hpp" // internal: the erase's and the retrieval's rounding

#include "assets.hpp"
#include "tinlod/closest_point.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/screen_weight.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/view.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace tinlod;

// float_up and float_down round toward +inf and -inf: the result is on the right side of d and
// the next float beyond it toward d is on the other side (the tightest such float).
TEST(FloatRounding, IsDirectedAndTight) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-30, 30);
    for (int i = 0; i < 100000; ++i) {
        const double d = std::ldexp(mantissa(rng), exponent(rng));
        const float up = float_up(d), down = float_down(d);
        ASSERT_GE(double(up), d);
        ASSERT_LE(double(down), d);
        ASSERT_LT(double(std::nextafter(up, -INFINITY)), d);
        ASSERT_GT(double(std::nextafter(down, INFINITY)), d);
    }
    EXPECT_EQ(float_up(0.5), 0.5f); // exact floats stay
    EXPECT_EQ(float_down(0.5), 0.5f);
}

// The rounding margin covers what storing a TIN triangle's corners as floats does to its plane:
// corners at exact grid positions (double) with float heights, as a DEM's samples are, rounded to
// float; at random points of the triangle, the plane through the float corners differs from the
// plane through the exact ones by at most rounding_margin(largest |x|, |y| there, its slope).
TEST(FloatRounding, MarginCoversTheFloatCornersOfAPlane) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    // z of the plane through three corners at (x, y).
    auto plane = [](const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c, double x,
                    double y, double *slope) {
        const glm::dvec3 n = glm::cross(b - a, c - a);
        if (slope)
            *slope = std::hypot(n.x, n.y) / std::abs(n.z);
        return a.z - (n.x * (x - a.x) + n.y * (y - a.y)) / n.z;
    };
    int tested = 0;
    for (int t = 0; t < 20000; ++t) {
        // A grid of spacing 1 to 100 m whose origin lies up to 10^7 from the axes.
        const double step = std::pow(10.0, 2.0 * unit(rng));
        const double ox = std::round(std::pow(10.0, 7.0 * unit(rng)) / step) * step + step / 3.0;
        const double oy = std::round(std::pow(10.0, 7.0 * unit(rng)) / step) * step + step / 7.0;
        const double relief = std::pow(10.0, 4.0 * unit(rng) - 1.0);
        glm::dvec3 exact[3];
        for (auto &e : exact)
            e = {ox + step * std::floor(8.0 * unit(rng)), oy + step * std::floor(8.0 * unit(rng)),
                 double(float(relief * (unit(rng) - 0.5)))};
        glm::dvec3 rounded[3];
        for (int i = 0; i < 3; ++i)
            rounded[i] = glm::dvec3(glm::vec3(exact[i]));
        const glm::dvec3 n = glm::cross(exact[1] - exact[0], exact[2] - exact[0]);
        const glm::dvec3 nr = glm::cross(rounded[1] - rounded[0], rounded[2] - rounded[0]);
        if (std::abs(n.z) < 0.1 * step * step || std::abs(nr.z) < 0.1 * step * step)
            continue; // degenerate in xy: no plane
        ++tested;
        for (int k = 0; k < 8; ++k) {
            double u = unit(rng), v = unit(rng);
            if (u + v > 1.0)
                u = 1.0 - u, v = 1.0 - v;
            const glm::dvec3 p = exact[0] + u * (exact[1] - exact[0]) + v * (exact[2] - exact[0]);
            double slope = 0.0;
            const double zr = plane(rounded[0], rounded[1], rounded[2], p.x, p.y, &slope);
            const double ze = plane(exact[0], exact[1], exact[2], p.x, p.y, nullptr);
            ASSERT_LE(std::abs(zr - ze),
                      rounding_margin(std::max(std::abs(p.x), std::abs(p.y)), slope))
                << "triangle " << t << ", point " << k;
        }
    }
    EXPECT_GT(tested, 10000);
}

// View::frame is a right-handed orthonormal frame along the axis with the screen's up in the
// vertical plane of the axis, and it is the frame in_frustum projects with: a point straight
// along right (up) at the viewport's half width (height) in pixels is on the frustum's edge.
TEST(ViewFrame, IsOrthonormalAndTheFrustumsFrame) {
    std::vector<View> views(3);
    views[1].eye = {0.0, 0.0, 5000.0}; // straight down: up is north
    views[1].at = {0.0, 0.0, 0.0};
    views[2].eye = {100.0, -300.0, 800.0};
    views[2].at = {-200.0, 900.0, 0.0};
    views[2].viewport_w = 512;
    for (const View &view : views) {
        const View::Frame f = view.frame();
        EXPECT_NEAR(glm::length(f.forward), 1.0, 1e-12);
        EXPECT_NEAR(glm::length(f.right), 1.0, 1e-12);
        EXPECT_NEAR(glm::length(f.up), 1.0, 1e-12);
        EXPECT_NEAR(glm::dot(f.forward, f.right), 0.0, 1e-12);
        EXPECT_NEAR(glm::dot(f.forward, f.up), 0.0, 1e-12);
        EXPECT_NEAR(glm::dot(glm::cross(f.right, f.up), -f.forward), 1.0, 1e-12);
        EXPECT_NEAR(f.right.z, 0.0, 1e-12); // the horizon stays level
        const double depth = 100.0, k = view.k();
        for (double s : {0.99, 1.01}) {
            const glm::dvec3 x =
                view.eye + depth * f.forward + f.right * (s * depth * 0.5 * view.viewport_w / k);
            const glm::dvec3 y =
                view.eye + depth * f.forward + f.up * (s * depth * 0.5 * view.viewport_h / k);
            EXPECT_EQ(view.in_frustum(x), s < 1.0);
            EXPECT_EQ(view.in_frustum(y), s < 1.0);
        }
    }
}

// significance.hpp's screen_weight and peripheral_factor are the Weigher's values (one
// definition), k / OD times the factor, whatever model the options name; the factor is 1 ahead
// and falls to the floor behind.
TEST(ScreenWeight, IsTheWeighersValue) {
    View view;
    view.eye = {0.0, 0.0, 500.0};
    view.at = {0.0, 1000.0, 0.0};
    SignificanceOptions options;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> coord(-3000.0, 3000.0);
    for (SpModel model : {SpModel::screen, SpModel::paper, SpModel::vertical}) {
        options.model = model;
        const Weigher weigher(view, options);
        for (int i = 0; i < 2000; ++i) {
            const glm::dvec3 p(coord(rng), coord(rng), coord(rng) / 10.0);
            const double od = glm::length(p - view.eye);
            ASSERT_EQ(screen_weight(view, p, options), weigher(p));
            ASSERT_EQ(peripheral_factor(view, p, options), weigher.peripheral(p));
            ASSERT_NEAR(weigher(p), view.k() / od * weigher.peripheral(p), 1e-12 * weigher(p));
            ASSERT_GE(weigher.peripheral(p), options.floor);
            ASSERT_LE(weigher.peripheral(p), 1.0);
        }
    }
    EXPECT_EQ(peripheral_factor(view, view.at, options), 1.0);
    EXPECT_EQ(peripheral_factor(view, view.eye - 1000.0 * view.axis(), options), options.floor);
    EXPECT_EQ(screen_weight(view, view.eye, options), INFINITY);
    EXPECT_EQ(Weigher(nullptr, options)(view.at), 1.0); // no view: every node weighs 1
}
