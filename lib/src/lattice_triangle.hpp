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
    LatticeTriangle(std::uint32_t w, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const std::uint32_t nodes[3] = {a, b, c};
        for (int k = 0; k < 3; ++k) {
            x_[k] = nodes[k] % w;
            y_[k] = nodes[k] / w;
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
    std::int64_t first_row = 0, last_row = -1;

  private:
    std::int64_t x_[3], y_[3], lo_ = 0, hi_ = 0;
};

} // namespace tinlod
