// The min-max triangulation of a hole (min_max_triangulation, ring_triangulation.hpp) against
// brute force written here, and what it lets `simplify --max-error` erase: a node whose hole some
// triangulation keeps within the bound goes, whichever triangulation the ears would have made.
#include "assets.hpp"

#include "erase/ring_triangulation.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <vector>

using namespace tinlod;
using tinlod::erase::clip_ears;
using tinlod::erase::min_max_triangulation;
using tinlod::erase::orient;
using tinlod::erase::RingTriangle;

namespace {

// A random star-shaped counter-clockwise polygon around the origin (a hole's ring), n nodes.
std::vector<glm::dvec2> star_polygon(std::mt19937 &rng, int n) {
    std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI), radius(0.3, 1.0);
    std::vector<double> a(static_cast<std::size_t>(n));
    for (double gap = 2.0 * M_PI; gap >= M_PI;) { // the origin inside: no gap of half a turn
        for (double &x : a)
            x = angle(rng);
        std::sort(a.begin(), a.end());
        gap = a.front() + 2.0 * M_PI - a.back();
        for (std::size_t i = 1; i < a.size(); ++i)
            gap = std::max(gap, a[i] - a[i - 1]);
    }
    std::vector<glm::dvec2> q;
    for (const double x : a) {
        const double r = radius(rng);
        q.push_back({r * std::cos(x), r * std::sin(x)});
    }
    return q;
}

// A cost for every triangle of ring nodes, random but fixed per triangle.
struct RandomCost {
    std::vector<double> table;
    int n;
    RandomCost(std::mt19937 &rng, int n) : table(std::size_t(n * n * n)), n(n) {
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (double &c : table)
            c = u(rng);
    }
    double operator()(int a, int b, int c) const {
        int s[3] = {a, b, c};
        std::sort(s, s + 3);
        return table[std::size_t((s[0] * n + s[1]) * n + s[2])];
    }
    // The largest cost of `count` triangles.
    double largest(const RingTriangle *t, int count) const {
        double most = 0.0;
        for (int k = 0; k < count; ++k)
            most = std::max(most, (*this)(t[k].a, t[k].b, t[k].c));
        return most;
    }
};

bool in_closed(const glm::dvec2 &a, const glm::dvec2 &b, const glm::dvec2 &c, const glm::dvec2 &p) {
    return orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0;
}

// The least largest cost over every triangulation of the polygon, by clipping every ear in turn
// (each triangulation of a simple polygon has an ear, and what is left is triangulated again).
double brute_min_max(const std::vector<glm::dvec2> &q, std::vector<int> left,
                     const RandomCost &cost, double so_far) {
    const int m = int(left.size());
    if (m == 3)
        return std::max(so_far, cost(left[0], left[1], left[2]));
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < m; ++i) {
        const int a = left[std::size_t((i + m - 1) % m)], b = left[std::size_t(i)],
                  c = left[std::size_t((i + 1) % m)];
        if (!(orient(q[std::size_t(a)], q[std::size_t(b)], q[std::size_t(c)]) > 0.0))
            continue;
        bool ear = true;
        for (const int j : left)
            if (j != a && j != b && j != c &&
                in_closed(q[std::size_t(a)], q[std::size_t(b)], q[std::size_t(c)],
                          q[std::size_t(j)]))
                ear = false;
        if (!ear)
            continue;
        std::vector<int> rest = left;
        rest.erase(rest.begin() + i);
        best = std::min(best, brute_min_max(q, rest, cost, std::max(so_far, cost(a, b, c))));
    }
    return best;
}

double polygon_area2(const std::vector<glm::dvec2> &q) {
    double twice = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i)
        twice += q[i].x * q[(i + 1) % q.size()].y - q[(i + 1) % q.size()].x * q[i].y;
    return twice;
}

// Whether the triangles tile the polygon: n - 2 of them, each counter-clockwise with no other ring
// node in it, their areas adding up to the polygon's, and every side of the ring in exactly one of
// them, every other edge in two (once each way).
void expect_triangulation(const std::vector<glm::dvec2> &q, const std::vector<RingTriangle> &t) {
    const int n = int(q.size());
    ASSERT_EQ(int(t.size()), n - 2);
    double area2 = 0.0;
    std::vector<int> uses(std::size_t(n * n), 0);
    for (const RingTriangle &x : t) {
        const int c[3] = {x.a, x.b, x.c};
        EXPECT_GT(orient(q[c[0]], q[c[1]], q[c[2]]), 0.0);
        area2 += orient(q[c[0]], q[c[1]], q[c[2]]);
        for (int j = 0; j < n; ++j) {
            if (j != c[0] && j != c[1] && j != c[2]) {
                EXPECT_FALSE(in_closed(q[c[0]], q[c[1]], q[c[2]], q[std::size_t(j)]));
            }
        }
        for (int k = 0; k < 3; ++k)
            ++uses[std::size_t(c[k] * n + c[(k + 1) % 3])];
    }
    EXPECT_NEAR(area2, polygon_area2(q), 1e-9);
    for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
            const int ab = uses[std::size_t(a * n + b)], ba = uses[std::size_t(b * n + a)];
            if (b == (a + 1) % n) {
                EXPECT_EQ(ab, 1) << "side " << a << "-" << b;
                EXPECT_EQ(ba, 0);
            } else if (a != (b + 1) % n) {
                EXPECT_EQ(ab, ba) << "edge " << a << "-" << b;
                EXPECT_LE(ab, 1);
            }
        }
    }
}

} // namespace

// On random star-shaped rings with a random cost per triangle: a triangulation of the ring, whose
// largest cost is the least over all triangulations (brute force), never above the ears', and -1
// exactly when that least is over the limit; a cost that stops at `stop` changes nothing.
TEST(MinMaxTriangulation, IsTheLeastLargestCostOverEveryTriangulation) {
    std::mt19937 rng(50);
    for (int trial = 0; trial < 400; ++trial) {
        const int n = 3 + trial % 6;
        const std::vector<glm::dvec2> q = star_polygon(rng, n);
        const RandomCost cost(rng, n);
        std::vector<int> all(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i)
            all[std::size_t(i)] = i;
        const double least = brute_min_max(q, all, cost, 0.0);
        ASSERT_TRUE(std::isfinite(least)) << "trial " << trial;

        std::array<RingTriangle, k_max_ring> out;
        int asked = 0;
        const auto exact = [&](int a, int b, int c, double) {
            ++asked;
            return cost(a, b, c);
        };
        const int count = min_max_triangulation(q.data(), n, INFINITY, exact, out.data());
        ASSERT_EQ(count, n - 2) << "trial " << trial;
        expect_triangulation(q, {out.begin(), out.begin() + count});
        const double largest = cost.largest(out.data(), count);
        EXPECT_EQ(largest, least) << "trial " << trial;
        EXPECT_LE(asked, n * (n - 1) * (n - 2) / 6) << "each triangle once at most";

        std::array<RingTriangle, k_max_ring> ears;
        ASSERT_EQ(clip_ears(q.data(), n, ears.data()), n - 2);
        EXPECT_LE(largest, cost.largest(ears.data(), n - 2)) << "trial " << trial;

        // The limit just under and at the least; a cost that gives up past its stop.
        const auto stopping = [&](int a, int b, int c, double stop) {
            const double x = cost(a, b, c);
            return x > stop ? stop + 1.0 : x;
        };
        EXPECT_EQ(
            min_max_triangulation(q.data(), n, std::nextafter(least, 0.0), stopping, out.data()),
            -1)
            << "trial " << trial;
        ASSERT_EQ(min_max_triangulation(q.data(), n, least, stopping, out.data()), n - 2);
        EXPECT_EQ(cost.largest(out.data(), n - 2), least) << "trial " << trial;
    }
}

// Rings with reflex nodes and nodes on a straight side (a grid TIN's rings have both): only
// triangles of positive area inside the ring, as brute force finds them.
TEST(MinMaxTriangulation, HandlesReflexAndStraightNodes) {
    // An L-shaped ring with a node in the middle of each long side.
    const std::vector<glm::dvec2> q = {{0, 0}, {1, 0}, {2, 0}, {2, 1},
                                       {1, 1}, {1, 2}, {0, 2}, {0, 1}};
    const int n = int(q.size());
    std::mt19937 rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        const RandomCost cost(rng, n);
        std::vector<int> all(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i)
            all[std::size_t(i)] = i;
        const double least = brute_min_max(q, all, cost, 0.0);
        std::array<RingTriangle, k_max_ring> out;
        const int count = min_max_triangulation(
            q.data(), n, INFINITY, [&](int a, int b, int c, double) { return cost(a, b, c); },
            out.data());
        ASSERT_EQ(count, n - 2);
        expect_triangulation(q, {out.begin(), out.begin() + count});
        EXPECT_EQ(cost.largest(out.data(), count), least) << "trial " << trial;
    }
}

// A 3 x 3 DEM whose centre lies on the line between two opposite side midpoints, at their mean
// height, and far from every other triangle over it; every other node is a corner or a side node
// off its corners' line, so none can go. The centre's hole has a triangulation that holds it
// exactly (the diagonal through it), whichever of the two midpoint pairs it is, so at a bound of
// 0.5 the centre goes in both: 8 nodes and 6 triangles, every sample within the bound.
TEST(SimplifyMaxError, ErasesANodeSomeTriangulationOfItsHoleHolds) {
    const std::string dir = test::temp_dir();
    for (const bool across : {false, true}) {
        // z[r][c], north row first: the centre 10 between midpoints 0 and 20 (a column, or a row
        // when `across`), the other two midpoints 0, the corners 30.
        unsigned z[3][3] = {{30, 0, 30}, {0, 10, 0}, {30, 20, 30}};
        if (across)
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < r; ++c)
                    std::swap(z[r][c], z[c][r]);
        std::vector<unsigned> samples;
        for (const auto &row : z)
            samples.insert(samples.end(), row, row + 3);
        const std::string png = dir + "/hole.png", out = dir + "/out.ply";
        std::ofstream(png, std::ios::binary) << test::png_bytes(3, 3, 0, 16, samples);
        const test::RunResult r = test::run_cli(
            "simplify " + png + " --cell 1 --max-error 0.5 --retrieve-share 0 -o " + out);
        ASSERT_EQ(r.status, 0) << r.err;
        const Mesh tin = read_mesh(out);
        EXPECT_EQ(tin.n_vertices(), 8u) << (across ? "across" : "along");
        EXPECT_EQ(tin.n_faces(), 6u) << (across ? "across" : "along");
        EXPECT_EQ(test::count_folded_faces(tin), 0);
        LoadOptions lo;
        lo.cell = 1.0;
        const TinError measured = measure_error(load_heightfield(png, lo), tin);
        EXPECT_EQ(measured.uncovered, 0);
        EXPECT_LE(measured.max_vertical, 0.5);
    }
}
