// What the second round of `simplify --max-error` speed-ups relies on
// (docs/decisions/025-simplify-speed-2.md): LatticeTriangle's rows walked without a division per
// row (for_each_row) are span()'s, row by row.
#include "lattice_triangle.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <tuple>
#include <vector>

using namespace tinlod;

namespace {

using Row = std::tuple<std::int64_t, std::int64_t, std::int64_t>; // (row, lo, hi), lo > hi: none

// Each row's span, from span() and from for_each_row, as the sets of samples they name (an
// empty row as (row, 1, 0)).
std::vector<Row> rows_by_span(const LatticeTriangle &t) {
    std::vector<Row> out;
    for (std::int64_t r = t.first_row; r <= t.last_row; ++r) {
        const auto [lo, hi] = t.span(r);
        out.emplace_back(r, lo <= hi ? lo : 1, lo <= hi ? hi : 0);
    }
    return out;
}

std::vector<Row> rows_walked(const LatticeTriangle &t) {
    std::vector<Row> out;
    EXPECT_TRUE(t.for_each_row([&](std::int64_t r, std::int64_t lo, std::int64_t hi) {
        out.emplace_back(r, lo <= hi ? lo : 1, lo <= hi ? hi : 0);
        return true;
    }));
    return out;
}

} // namespace

// Random triangles, small (many rows with samples on the sides, horizontal edges, degenerate
// ones) and long and thin over a wide lattice (quotients and remainders carried over hundreds of
// rows), both orientations: the same span on every row.
TEST(SimplifySpeed2, ForEachRowGivesSpansRows) {
    std::mt19937 rng(25);
    int horizontal = 0, degenerate = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const bool wide = trial % 4 == 3;
        const std::int64_t side = wide ? 1025 : 12;
        std::uniform_int_distribution<std::int64_t> coord(0, side - 1);
        std::uint32_t node[3];
        std::int64_t y[3];
        for (int k = 0; k < 3; ++k) {
            y[k] = coord(rng);
            node[k] = std::uint32_t(y[k] * side + coord(rng));
        }
        const LatticeTriangle t(std::uint32_t(side), node[0], node[1], node[2]);
        ASSERT_EQ(rows_walked(t), rows_by_span(t))
            << "trial " << trial << ": nodes " << node[0] << " " << node[1] << " " << node[2];
        horizontal += y[0] == y[1] || y[1] == y[2] || y[2] == y[0];
        degenerate += t.last_row < t.first_row;
    }
    EXPECT_GT(horizontal, 500);
    EXPECT_GT(degenerate, 50);
}

TEST(SimplifySpeed2, ForEachRowStopsWhenARowSaysSo) {
    const LatticeTriangle t(16, 0, 6, 6 * 16);
    int rows = 0;
    EXPECT_FALSE(
        t.for_each_row([&](std::int64_t, std::int64_t, std::int64_t) { return ++rows < 3; }));
    EXPECT_EQ(rows, 3);
}
