// The geometric concepts with one definition each (#47 item 4): float rounding and the plane's
// rounding margin (lib/src/float_rounding.hpp), a TIN triangle's plane and a node's deviation
// (lib/src/triangle_plane.hpp), the projection frame (View::frame), the screen weight
// (tinlod/screen_weight.hpp) as significance.hpp's functions give it.
#include "../lib/src/float_rounding.hpp" // internal: the erase's and the retrieval's rounding
#include "../lib/src/triangle_plane.hpp" // internal: a TIN triangle's plane, a node's deviation

#include "assets.hpp"
#include "tinlod/closest_point.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/screen_weight.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/view.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

using namespace tinlod;

// p rounded to float, as a mesh stores it. Through volatile floats: GCC 12's vectoriser at -O2
// drops the round trip of glm::dvec3(glm::vec3(p)).
static glm::dvec3 to_float(const glm::dvec3 &p) {
    const volatile float x = float(p.x), y = float(p.y), z = float(p.z);
    return {x, y, z};
}

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
            rounded[i] = to_float(exact[i]);
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
// definition), k / OD times the factor, the erase bound's weight in the screen and paper models;
// the factor is 1 ahead and falls to the floor behind.
TEST(ScreenWeight, IsTheWeighersValue) {
    View view;
    view.eye = {0.0, 0.0, 500.0};
    view.at = {0.0, 1000.0, 0.0};
    SignificanceOptions options;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> coord(-3000.0, 3000.0);
    for (SpModel model : {SpModel::screen, SpModel::paper}) {
        const Weigher weigher(Significance::of(model, view, options));
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
    EXPECT_EQ(Weigher(Significance::vertical())(view.at), 1.0); // every node weighs 1
}

// A random TIN triangle as the mesh holds it: corners at exact grid positions (spacing 1 to
// 100 m, the grid's origin up to 10^7 from the axes) with float heights, and those corners
// rounded to float; `flat` gives its corners one height.
struct GridTriangle {
    double step;
    std::array<glm::dvec3, 3> exact, rounded;
};

static GridTriangle grid_triangle(std::mt19937 &rng, bool flat) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    GridTriangle t;
    t.step = std::pow(10.0, 2.0 * unit(rng));
    const double ox = std::round(std::pow(10.0, 7.0 * unit(rng)) / t.step) * t.step + t.step / 3.0;
    const double oy = std::round(std::pow(10.0, 7.0 * unit(rng)) / t.step) * t.step + t.step / 7.0;
    const double relief = std::pow(10.0, 4.0 * unit(rng) - 1.0);
    const double level = double(float(relief * (unit(rng) - 0.5)));
    for (int i = 0; i < 3; ++i) {
        t.exact[i] = {ox + t.step * std::floor(8.0 * unit(rng)),
                      oy + t.step * std::floor(8.0 * unit(rng)),
                      flat ? level : double(float(relief * (unit(rng) - 0.5)))};
        t.rounded[i] = to_float(t.exact[i]);
    }
    return t;
}

// Twice the signed area in xy, and z of the plane through a, b, c at (x, y), in long double.
static long double area2(const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c) {
    return ((long double)b.x - a.x) * ((long double)c.y - a.y) -
           ((long double)c.x - a.x) * ((long double)b.y - a.y);
}

static long double exact_height(const std::array<glm::dvec3, 3> &t, double x, double y) {
    const glm::dvec3 p(x, y, 0.0);
    const long double w0 = area2(t[1], t[2], p), w1 = area2(t[2], t[0], p),
                      w2 = area2(t[0], t[1], p);
    return (w0 * t[0].z + w1 * t[1].z + w2 * t[2].z) / area2(t[0], t[1], t[2]);
}

// A TrianglePlane (and its second evaluation, the gradient by rows) passes through its corners
// and is the plane through them: up to the double rounding of an affine form whose constant term
// cancels the corners' heights over coordinates up to 10^7 times the spacing.
TEST(TrianglePlane, IsThePlaneThroughItsCorners) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int tested = 0;
    for (int n = 0; n < 20000; ++n) {
        const GridTriangle t = grid_triangle(rng, n % 5 == 0);
        const auto &c = t.rounded;
        if (std::abs(area2(c[0], c[1], c[2])) < 0.1 * t.step * t.step)
            continue; // degenerate in xy: no plane
        ++tested;
        const TrianglePlane plane(c[0], c[1], c[2]);
        const TrianglePlane::Rows rows = TrianglePlane::rows(c[0], c[1], c[2]);
        double coord = 0.0, zmax = 0.0;
        for (const glm::dvec3 &p : c) {
            coord = std::max({coord, std::abs(p.x), std::abs(p.y)});
            zmax = std::max(zmax, std::abs(p.z));
        }
        const double hair = 1e-13 * (zmax + plane.slope() * coord) * (1.0 + coord / t.step);
        for (const glm::dvec3 &p : c) {
            ASSERT_NEAR(plane.height(p.x, p.y), p.z, hair) << "triangle " << n;
            ASSERT_NEAR(rows.deviation(rows.start(p.y), p.x, p.z), 0.0, hair) << "triangle " << n;
        }
        for (int k = 0; k < 8; ++k) {
            const double x = c[0].x + t.step * 8.0 * (unit(rng) - 0.5),
                         y = c[0].y + t.step * 8.0 * (unit(rng) - 0.5);
            const double z = double(exact_height(c, x, y));
            ASSERT_NEAR(plane.height(x, y), z, hair) << "triangle " << n << ", point " << k;
            ASSERT_NEAR(rows.deviation(rows.start(y), x, z), 0.0, hair);
        }
        const double gx = double((exact_height(c, c[0].x + t.step, c[0].y) - c[0].z) / t.step),
                     gy = double((exact_height(c, c[0].x, c[0].y + t.step) - c[0].z) / t.step);
        ASSERT_NEAR(plane.slope(), std::hypot(gx, gy), 1e-9 * plane.slope() + hair / t.step);
    }
    EXPECT_GT(tested, 10000);
}

// The widened deviation of a sample as the mesh holds it (float point, plane through the float
// corners) never understates its exact deviation (exact position, plane through the exact
// corners, in long double), on lattice samples and on random points of the triangle; short of
// the widening it does, by up to the float corners' rounding. The hair is the double evaluation's
// own rounding (as above), which the erase's limit leaves room for (sweep.cpp, erase_limit).
TEST(TrianglePlane, WidenedDeviationBoundsTheExactDeviation) {
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int tested = 0, understated = 0;
    for (int n = 0; n < 20000; ++n) {
        const GridTriangle t = grid_triangle(rng, n % 5 == 0);
        if (std::abs(area2(t.rounded[0], t.rounded[1], t.rounded[2])) < 0.1 * t.step * t.step ||
            std::abs(area2(t.exact[0], t.exact[1], t.exact[2])) < 0.1 * t.step * t.step)
            continue;
        ++tested;
        const TrianglePlane plane(t.rounded[0], t.rounded[1], t.rounded[2]);
        double zmax = 0.0;
        for (const glm::dvec3 &p : t.exact)
            zmax = std::max(zmax, std::abs(p.z));
        for (int k = 0; k < 16; ++k) {
            double u = unit(rng), v = unit(rng);
            if (u + v > 1.0)
                u = 1.0 - u, v = 1.0 - v;
            glm::dvec3 exact =
                t.exact[0] + u * (t.exact[1] - t.exact[0]) + v * (t.exact[2] - t.exact[0]);
            if (k % 2 == 0) // a lattice sample of the triangle (its corner if none is drawn)
                for (int tries = 0; tries < 20; ++tries) {
                    const glm::dvec3 q(t.exact[0].x + t.step * std::round(16.0 * unit(rng) - 8.0),
                                       t.exact[0].y + t.step * std::round(16.0 * unit(rng) - 8.0),
                                       0.0);
                    const long double s0 = area2(t.exact[1], t.exact[2], q),
                                      s1 = area2(t.exact[2], t.exact[0], q),
                                      s2 = area2(t.exact[0], t.exact[1], q);
                    exact = t.exact[std::size_t(k % 3)];
                    if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) {
                        exact = q;
                        break;
                    }
                }
            exact.z = double(
                float(exact_height(t.exact, exact.x, exact.y) + zmax * 1e-3 * (unit(rng) - 0.5)));
            const long double truth =
                std::abs((long double)exact.z - exact_height(t.exact, exact.x, exact.y));
            const glm::dvec3 p = to_float(exact);
            const double coord = std::max(std::abs(p.x), std::abs(p.y));
            const double hair = 1e-13 * (zmax + plane.slope() * coord) * (1.0 + coord / t.step);
            ASSERT_GE(plane.deviation(p) + hair, double(truth)) << "triangle " << n << ", " << k;
            ASSERT_GE(plane.deviation(p.x, p.y, p.z,
                                      plane.margin_over(t.rounded[0], t.rounded[1], t.rounded[2])),
                      plane.deviation(p));
            understated += double(truth) > plane.vertical(p) + hair;
        }
    }
    EXPECT_GT(tested, 10000);
    EXPECT_GT(understated, 0); // the widening is needed
}

// A node's deviation is the TIN plane's widened deviation on a TIN, and on a surface mesh its
// distance to the triangle: the nearest of a fine sampling of the triangle, within its spacing.
TEST(NodeDeviation, IsTheWidenedVerticalOrTheDistanceToTheTriangle) {
    std::mt19937 rng(29);
    std::uniform_real_distribution<double> coord(-10.0, 10.0);
    for (int n = 0; n < 300; ++n) {
        const glm::dvec3 a(coord(rng), coord(rng), coord(rng)),
            b(coord(rng), coord(rng), coord(rng)), c(coord(rng), coord(rng), coord(rng));
        const glm::dvec3 p(coord(rng), coord(rng), coord(rng));
        if (std::abs(area2(a, b, c)) > 1.0) {
            const TrianglePlane plane(a, b, c);
            ASSERT_EQ(node_deviation(true, plane, p, a, b, c), plane.deviation(p));
        }
        constexpr int k = 200;
        double nearest = INFINITY;
        for (int i = 0; i <= k; ++i)
            for (int j = 0; i + j <= k; ++j)
                nearest = std::min(nearest, glm::length(p - (a + (b - a) * (double(i) / k) +
                                                             (c - a) * (double(j) / k))));
        const double spacing =
            std::max({glm::length(b - a), glm::length(c - a), glm::length(c - b)}) / k;
        const double d = node_deviation(false, TrianglePlane(), p, a, b, c);
        ASSERT_LE(d, nearest + 1e-12) << "triangle " << n;
        ASSERT_GE(d, nearest - spacing) << "triangle " << n;
    }
}
