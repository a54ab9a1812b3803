// The lattice samples inside a triangle whose corners are lattice samples, row by row, exactly
// (integer edge tests in lattice coordinates): the node erase's scans of a grid TIN's faces
// (lib/src/erase/lattice_scan.hpp) and the greedy inserter's (greedy.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>

namespace tinlod {

inline std::int64_t floor_div(std::int64_t a, std::int64_t b) {
    const std::int64_t q = a / b;
    return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

// The lattice samples in the closed triangle with corner nodes a, b, c: its rows, and per row the
// span of columns, exactly (integer edge tests in lattice coordinates).
class LatticeTriangle {
  public:
    LatticeTriangle(std::uint32_t w, std::uint32_t a, std::uint32_t b, std::uint32_t c)
        : LatticeTriangle({a % w, b % w, c % w}, {a / w, b / w, c / w}) {}
    // The triangle with corners (x[k], y[k]).
    LatticeTriangle(const std::int64_t (&x)[3], const std::int64_t (&y)[3]) {
        for (int k = 0; k < 3; ++k) {
            x_[k] = x[k];
            y_[k] = y[k];
        }
        const std::int64_t o =
            (x_[1] - x_[0]) * (y_[2] - y_[0]) - (y_[1] - y_[0]) * (x_[2] - x_[0]);
        if (o < 0) {
            std::swap(x_[1], x_[2]);
            std::swap(y_[1], y_[2]);
        }
        first_row = std::min({y_[0], y_[1], y_[2]});
        last_row = o == 0 ? first_row - 1 : std::max({y_[0], y_[1], y_[2]});
        lo_ = std::min({x_[0], x_[1], x_[2]});
        hi_ = std::max({x_[0], x_[1], x_[2]});
    }
    // The columns [lo, hi] of row y inside the triangle (lo > hi when none).
    std::pair<std::int64_t, std::int64_t> span(std::int64_t y) const {
        std::int64_t lo = lo_, hi = hi_;
        for (int k = 0; k < 3; ++k) {
            // Counter-clockwise: inside is left of each edge p -> q, B * (x - px) <= A.
            const int l = (k + 1) % 3;
            const std::int64_t a = (x_[l] - x_[k]) * (y - y_[k]), b = y_[l] - y_[k];
            if (b > 0)
                hi = std::min(hi, x_[k] + floor_div(a, b));
            else if (b < 0)
                lo = std::max(lo, x_[k] - floor_div(a, -b));
            else if (a < 0)
                return {1, 0};
        }
        return {lo, hi};
    }
    // row(y, lo, hi) for each row y from first_row to last_row, with span(y) as [lo, hi] (lo > hi
    // when the row holds none), until it returns false; false when it stopped. Each sloped edge's
    // floor_div is carried from row to row as a quotient and a remainder: two divisions per edge,
    // where span() makes two a row (docs/decisions/025-simplify-speed-2.md).
    template <class Row> bool for_each_row(const Row &row) const {
        struct Edge {
            std::int64_t x, b, q, r, dq, dr; // x + or - floor_div(a, b) = q, a - q b = r; a
                                             // grows by d = dq b + dr a row
        };
        Edge hi_edges[3], lo_edges[3];
        std::int64_t flat_d[3], flat_y[3]; // horizontal edges: their d and row
        int highs = 0, lows = 0, flats = 0;
        for (int k = 0; k < 3; ++k) {
            const int l = (k + 1) % 3;
            const std::int64_t d = x_[l] - x_[k], b = y_[l] - y_[k];
            if (b == 0) {
                flat_d[flats] = d;
                flat_y[flats++] = y_[k];
                continue;
            }
            Edge &e = b > 0 ? hi_edges[highs++] : lo_edges[lows++];
            e.x = x_[k];
            e.b = b > 0 ? b : -b;
            divide(d * (first_row - y_[k]), e.b, e.q, e.r);
            divide(d, e.b, e.dq, e.dr);
        }
        const auto step = [](Edge &e) {
            e.q += e.dq;
            e.r += e.dr;
            if (e.r >= e.b) {
                e.r -= e.b;
                ++e.q;
            }
        };
        for (std::int64_t y = first_row; y <= last_row; ++y) {
            std::int64_t lo = lo_, hi = hi_;
            for (int k = 0; k < highs; ++k)
                hi = std::min(hi, hi_edges[k].x + hi_edges[k].q);
            for (int k = 0; k < lows; ++k)
                lo = std::max(lo, lo_edges[k].x - lo_edges[k].q);
            for (int k = 0; k < flats; ++k)
                if (flat_d[k] * (y - flat_y[k]) < 0)
                    lo = hi + 1; // outside the horizontal edge: span() has none
            if (!row(y, lo, hi))
                return false;
            for (int k = 0; k < highs; ++k)
                step(hi_edges[k]);
            for (int k = 0; k < lows; ++k)
                step(lo_edges[k]);
        }
        return true;
    }
    std::int64_t first_row = 0, last_row = -1;

  private:
    // q = floor_div(a, b) and r = a - q b (b > 0), without a division in the cases a small
    // triangle's edges mostly give (|a| <= b).
    static void divide(std::int64_t a, std::int64_t b, std::int64_t &q, std::int64_t &r) {
        if (a >= 0 && a < b)
            q = 0;
        else if (a < 0 && a >= -b)
            q = -1;
        else
            q = floor_div(a, b);
        r = a - q * b;
    }
    std::int64_t x_[3], y_[3], lo_ = 0, hi_ = 0;
};

// A triangle whose box holds at most this many samples is cheaper to scan over its box with the
// corners' edge tests (an add per sample and edge) than a row span at a time (two divisions a row):
// most triangles of a fine TIN hold a few samples (docs/decisions/024-simplify-speed.md).
inline constexpr std::int64_t k_small_box = 64;

// The samples in the box of the triangle with lattice corners (x[k], y[k]).
inline std::int64_t box_samples(const std::int64_t (&x)[3], const std::int64_t (&y)[3]) {
    return (std::max({x[0], x[1], x[2]}) - std::min({x[0], x[1], x[2]}) + 1) *
           (std::max({y[0], y[1], y[2]}) - std::min({y[0], y[1], y[2]}) + 1);
}

// The lattice samples in the closed triangle with corners (x[k], y[k]), the set LatticeTriangle
// gives, in row order over its box: visit(x, y) for each until it returns false. Returns false
// when a visit stopped the scan.
template <class Visit>
inline bool visit_box(const std::int64_t (&x)[3], const std::int64_t (&y)[3], const Visit &visit) {
    const std::int64_t o = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if (o == 0)
        return true;                                        // no samples, as LatticeTriangle has it
    const int order[3] = {0, o > 0 ? 1 : 2, o > 0 ? 2 : 1}; // counter-clockwise
    const std::int64_t x0 = std::min({x[0], x[1], x[2]}), x1 = std::max({x[0], x[1], x[2]});
    const std::int64_t y0 = std::min({y[0], y[1], y[2]}), y1 = std::max({y[0], y[1], y[2]});
    // Edge k's test at (c, r): (x_l - x_k) (r - y_k) - (y_l - y_k) (c - x_k) >= 0 inside.
    std::int64_t step[3], down[3], start[3];
    for (int k = 0; k < 3; ++k) {
        const int a = order[k], b = order[(k + 1) % 3];
        step[k] = y[a] - y[b];
        down[k] = x[b] - x[a];
        start[k] = down[k] * (y0 - y[a]) + step[k] * (x0 - x[a]);
    }
    for (std::int64_t r = y0; r <= y1; ++r) {
        std::int64_t e0 = start[0], e1 = start[1], e2 = start[2], c = x0;
        // The row's inside samples are one run (the triangle is convex): none after it.
        for (; c <= x1 && (e0 | e1 | e2) < 0; ++c, e0 += step[0], e1 += step[1], e2 += step[2]) {
        }
        for (; c <= x1 && (e0 | e1 | e2) >= 0; ++c, e0 += step[0], e1 += step[1], e2 += step[2])
            if (!visit(c, r))
                return false;
        for (int k = 0; k < 3; ++k)
            start[k] += down[k];
    }
    return true;
}

// The lattice samples in the closed triangle with corners (x[k], y[k]) but its corners, in row
// order: visit(x, y) for each until it returns false. Returns false when a visit stopped the scan.
// A small triangle over its box (visit_box), a larger one a row span at a time (for_each_row), the
// corners looked for on their own rows only.
template <class Visit>
inline bool visit_inside(const std::int64_t (&x)[3], const std::int64_t (&y)[3],
                         const Visit &visit) {
    const auto corner = [&](std::int64_t c, std::int64_t r) {
        return (c == x[0] && r == y[0]) || (c == x[1] && r == y[1]) || (c == x[2] && r == y[2]);
    };
    if (box_samples(x, y) <= k_small_box)
        return visit_box(
            x, y, [&](std::int64_t c, std::int64_t r) { return corner(c, r) || visit(c, r); });
    return LatticeTriangle(x, y).for_each_row(
        [&](std::int64_t r, std::int64_t lo, std::int64_t hi) {
            if (r == y[0] || r == y[1] || r == y[2]) {
                for (std::int64_t c = lo; c <= hi; ++c)
                    if (!corner(c, r) && !visit(c, r))
                        return false;
                return true;
            }
            for (std::int64_t c = lo; c <= hi; ++c)
                if (!visit(c, r))
                    return false;
            return true;
        });
}

} // namespace tinlod
