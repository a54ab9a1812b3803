// What the faster `simplify --max-error` relies on (docs/decisions/024-simplify-speed.md, 039): a
// small triangle's samples visited over its box (visit_box) are LatticeTriangle's, in row order, so
// are visit_inside's but the corners, and the erase's early ends keep the bound and the
// fewest-triangles result it had.
#include "assets.hpp"

#include "lattice_triangle.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <utility>
#include <vector>

using namespace tinlod;

namespace {

using Sample = std::pair<std::int64_t, std::int64_t>; // (column, row)

// The samples of the closed lattice triangle, row by row from LatticeTriangle's spans.
std::vector<Sample> by_spans(const std::int64_t (&x)[3], const std::int64_t (&y)[3]) {
    constexpr std::uint32_t w = 64;
    const LatticeTriangle t(w, std::uint32_t(y[0] * w + x[0]), std::uint32_t(y[1] * w + x[1]),
                            std::uint32_t(y[2] * w + x[2]));
    std::vector<Sample> out;
    for (std::int64_t r = t.first_row; r <= t.last_row; ++r) {
        const auto [lo, hi] = t.span(r);
        for (std::int64_t c = lo; c <= hi; ++c)
            out.emplace_back(c, r);
    }
    return out;
}

} // namespace

// Random triangles in a 12 x 12 box (so many have samples on their sides, and some are
// degenerate), both orientations: the same samples in the same order.
TEST(SimplifySpeed, VisitBoxGivesTheLatticeTrianglesSamplesInRowOrder) {
    std::mt19937 rng(24);
    std::uniform_int_distribution<std::int64_t> coord(0, 11);
    int degenerate = 0, with_side_samples = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        std::int64_t x[3], y[3];
        for (int k = 0; k < 3; ++k) {
            x[k] = coord(rng);
            y[k] = coord(rng);
        }
        std::vector<Sample> boxed;
        EXPECT_TRUE(visit_box(x, y, [&](std::int64_t c, std::int64_t r) {
            boxed.emplace_back(c, r);
            return true;
        }));
        const std::vector<Sample> spans = by_spans(x, y);
        ASSERT_EQ(boxed, spans) << "corners (" << x[0] << "," << y[0] << ") (" << x[1] << ","
                                << y[1] << ") (" << x[2] << "," << y[2] << ")";
        const std::int64_t o = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        degenerate += o == 0;
        with_side_samples += std::int64_t(spans.size()) > (std::abs(o) + 2) / 2 + 1;
        EXPECT_LE(std::int64_t(spans.size()), box_samples(x, y));
    }
    EXPECT_GT(degenerate, 100);
    EXPECT_GT(with_side_samples, 1000);
}

TEST(SimplifySpeed, VisitBoxStopsWhenAVisitSaysSo) {
    const std::int64_t x[3] = {0, 6, 0}, y[3] = {0, 0, 6};
    int visits = 0;
    EXPECT_FALSE(visit_box(x, y, [&](std::int64_t, std::int64_t) { return ++visits < 5; }));
    EXPECT_EQ(visits, 5);
}

// Random triangles in a 40 x 40 box (small ones scanned over their box, larger ones by row spans,
// k_small_box), both orientations: visit_inside gives LatticeTriangle's samples but the corners, in
// row order, and stops when a visit says so.
TEST(SimplifySpeed, VisitInsideGivesTheSamplesButTheCornersInRowOrder) {
    std::mt19937 rng(39);
    std::uniform_int_distribution<std::int64_t> side(0, 39);
    int small = 0, large = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        std::int64_t x[3], y[3];
        const std::int64_t reach = trial % 2 == 0 ? 8 : 40; // half of them small
        for (int k = 0; k < 3; ++k) {
            x[k] = side(rng) % reach;
            y[k] = side(rng) % reach;
        }
        std::vector<Sample> inside;
        EXPECT_TRUE(visit_inside(x, y, [&](std::int64_t c, std::int64_t r) {
            inside.emplace_back(c, r);
            return true;
        }));
        std::vector<Sample> expected;
        for (const Sample &p : by_spans(x, y))
            if (p != Sample(x[0], y[0]) && p != Sample(x[1], y[1]) && p != Sample(x[2], y[2]))
                expected.push_back(p);
        ASSERT_EQ(inside, expected) << "corners (" << x[0] << "," << y[0] << ") (" << x[1] << ","
                                    << y[1] << ") (" << x[2] << "," << y[2] << ")";
        (box_samples(x, y) <= k_small_box ? small : large) += expected.size() > 2;
        if (expected.size() > 2) {
            std::size_t visits = 0;
            EXPECT_FALSE(visit_inside(
                x, y, [&](std::int64_t, std::int64_t) { return ++visits < expected.size() / 2; }));
            EXPECT_EQ(visits, expected.size() / 2);
        }
    }
    EXPECT_GT(small, 1000);
    EXPECT_GT(large, 1000);
}

// A terrain of ridges and pits at several scales (a 16-bit PNG), where many of the greedy
// insertion's nodes cannot go (the erase ends their evaluations early) and many holes need the
// min-max triangulation: every sample covered and within the bound, no fold, some nodes erased.
TEST(SimplifySpeed, SimplifyAtABoundHoldsItWithTheEarlyEnds) {
    const std::string dir = test::temp_dir();
    constexpr int w = 160, h = 130;
    std::vector<unsigned> samples;
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c)
            samples.push_back(unsigned(std::lround(
                60.0 + 40.0 * std::sin(c * 0.07) * std::cos(r * 0.05) +
                9.0 * std::sin(c * 0.31 + r * 0.2) + 3.0 * std::cos(c * 1.3) * std::sin(r * 1.1))));
    const std::string png = dir + "/ridges.png", out = dir + "/out.ply";
    std::ofstream(png, std::ios::binary) << test::png_bytes(w, h, 0, 16, samples);
    LoadOptions lo;
    lo.cell = 1.0;
    const Heightfield hf = load_heightfield(png, lo);
    for (const double bound : {0.5, 2.0, 8.0}) {
        const test::RunResult r = test::run_cli("simplify " + png + " --cell 1 --max-error " +
                                                std::to_string(bound) + " -o " + out);
        ASSERT_EQ(r.status, 0) << r.err;
        const Mesh tin = read_mesh(out);
        EXPECT_EQ(test::count_folded_faces(tin), 0) << bound;
        const TinError measured = measure_error(hf, tin);
        EXPECT_EQ(measured.uncovered, 0) << bound;
        EXPECT_LE(measured.max_vertical, bound) << bound;
        EXPECT_LT(tin.n_faces(), std::size_t(2 * (w - 1) * (h - 1))) << bound; // some erased
    }
}
