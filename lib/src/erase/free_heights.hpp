// After the flip pass at a vertical bound on a DEM: a node's height need not be its sample's, only
// every sample within the bound of the TIN over it. Each interior node still standing is tried
// again, its hole triangulated (the min-max triangulation of how far its samples miss the limit
// with the ring's interior nodes moved as far as their own samples let them), with those nodes
// free to move: a small linear programme says whether heights exist that keep every sample of the
// new triangles and of every triangle around a moved node within the limit.
// The outline's nodes keep their heights (a neighbouring tile meets them). The nodes near an erase
// are tried again, until none goes (docs/decisions/034-free-heights.md).
#pragma once

#include "lattice_triangle.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace tinlod::erase {

struct FreeHeightsStats {
    std::int64_t erased = 0; // nodes erased by the pass
};

// The pass on `tin` (a TIN over hf's samples, origin = sample id, as erase_dem returns it), each
// sample within `limit` (vertically) of the triangle over it, checked exactly at the heights
// written (floats). Returns the TIN it leaves (the nodes left in tin's order, origin = sample id,
// xy unchanged), and its counts in `stats` when given. Runs last: the flip pass and the erase
// take a node's height to be its sample's.
Mesh free_heights(const Mesh &tin, const Heightfield &hf, double limit, int max_valence,
                  FreeHeightsStats *stats = nullptr);

// The samples of the closed lattice triangle with corners (x[k], y[k]) (counter-clockwise, a box
// of over k_small_box samples) but its corners, in row order (LatticeTriangle), less those a cheap
// test passes over: two planes through heights down[k] and up[k] at the corners, stepped along
// each row, pass over a sample of height h when down - h >= floor and up - h <= ceiling (both read
// at each sample: a visit may move them). visit(x, y, sa, sb, sc) for the others, with the doubled
// lattice areas that weigh the corners, until it returns false; false when it stopped. The steps
// round (far under 1e-9 m on a DEM): a test wants a margin over that (the pass's k_near).
template <class Visit>
bool scan_stepped(const Heightfield &hf, const std::int64_t (&x)[3], const std::int64_t (&y)[3],
                  const std::array<double, 3> &down, const std::array<double, 3> &up,
                  const double &floor, const double &ceiling, const Visit &visit) {
    const auto area = [&](int k, std::int64_t px, std::int64_t py) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        return (x[a] - px) * (y[b] - py) - (y[a] - py) * (x[b] - px);
    };
    const std::int64_t step[3] = {y[1] - y[2], y[2] - y[0], y[0] - y[1]};
    const double whole = double(area(0, x[0], y[0]));
    const auto plane = [&](const std::array<double, 3> &z, double a0, double a1, double a2) {
        return (a0 * z[0] + a1 * z[1] + a2 * z[2]) / whole;
    };
    const double d_down = plane(down, double(step[0]), double(step[1]), double(step[2])),
                 d_up = plane(up, double(step[0]), double(step[1]), double(step[2]));
    return LatticeTriangle(x, y).for_each_row(
        [&](std::int64_t py, std::int64_t lo, std::int64_t hi) {
            if (lo > hi)
                return true;
            const std::int64_t a0 = area(0, lo, py), a1 = area(1, lo, py), a2 = area(2, lo, py);
            double l = plane(down, double(a0), double(a1), double(a2)),
                   u = plane(up, double(a0), double(a1), double(a2));
            const float *z = &hf.z[std::size_t(py) * std::size_t(hf.width)];
            for (std::int64_t px = lo; px <= hi; ++px, l += d_down, u += d_up) {
                const double h = double(z[px]);
                if (l - h >= floor && u - h <= ceiling)
                    continue;
                if ((px == x[0] && py == y[0]) || (px == x[1] && py == y[1]) ||
                    (px == x[2] && py == y[2]))
                    continue;
                const std::int64_t k = px - lo;
                if (!visit(px, py, double(a0 + k * step[0]), double(a1 + k * step[1]),
                           double(a2 + k * step[2])))
                    return false;
            }
            return true;
        });
}

// Boxes [low_k, high_k] of n variables narrowed by rows |sum_k w_k z_(var_k) - r| <= limit, each on
// at most three variables (var -1: none) with weights >= 0: the other variables' boxes bound each
// one's share of a row. A row whose range over the boxes misses [r - limit, r + limit] by more
// than k_slack rules out every z in the boxes: a necessary condition of the free heights'
// programme at a fraction of its cost (the boxes hold every z that keeps the rows within the
// limit, give or take k_slack).
class BoxNarrowing {
  public:
    // What the boxes may be off by (far over their rounding, far under a limit), and the least
    // weight a row narrows its variable by (a smaller one bounds it little).
    static constexpr double k_slack = 1e-7, k_min_weight = 1e-3;

    // The boxes to start from, and the limit.
    void reset(const std::vector<double> &low, const std::vector<double> &high, double limit);
    // Narrows the boxes by the row; false when it rules them out (inline: the pass calls it for
    // each row it makes).
    bool add(const std::array<int, 3> &var, const std::array<double, 3> &w, double r);
    double low(int k) const { return low_[std::size_t(k)]; }
    double high(int k) const { return high_[std::size_t(k)]; }

  private:
    std::vector<double> low_, high_;
    double limit_ = 0.0;
};

inline bool BoxNarrowing::add(const std::array<int, 3> &var, const std::array<double, 3> &w,
                              double r) {
    double least = 0.0, most = 0.0;
    for (std::size_t k = 0; k < 3; ++k)
        if (var[k] >= 0) {
            least += w[k] * low_[std::size_t(var[k])];
            most += w[k] * high_[std::size_t(var[k])];
        }
    // How far the row's range may rise and fall before it leaves its interval.
    const double rise = r + limit_ - least, fall = most - (r - limit_);
    if (rise < -k_slack || fall < -k_slack)
        return false;
    // Each variable's share of the range is at most all of it: most rows narrow nothing.
    if (rise >= most - least && fall >= most - least)
        return true;
    for (std::size_t k = 0; k < 3; ++k) {
        if (var[k] < 0 || w[k] < k_min_weight)
            continue;
        double &lo = low_[std::size_t(var[k])], &hi = high_[std::size_t(var[k])];
        const double span = w[k] * (hi - lo);
        if (rise < span - k_slack)
            hi = lo + rise / w[k];
        if (fall < span - k_slack)
            lo = hi - fall / w[k]; // from the lowered top, if so: a looser bound, still one
        if (lo > hi + k_slack)
            return false;
    }
    return true;
}

// The least L-infinity fit: z (n values) minimising max_i |a_i . z - b_i| over rows a_i added one
// at a time, by the simplex method on its dual (n + 1 equality rows, two columns a row). A solve
// after more rows are added goes on from the last one's basis (rows a fit misses come in a few at
// a time), and the tableau's memory is kept from fit to fit.
class ChebyshevFit {
  public:
    // A fit of n variables, no rows yet.
    void reset(int n);
    // Adds the row (a: n values, b).
    void add_row(const double *a, double b);
    // The least maximum over the rows added, its z in `z`; stops early with a value over
    // `give_up` once the least is known to exceed it; +inf when the method does not settle.
    double solve(double give_up, std::vector<double> &z);

  private:
    void pivot(std::size_t r, std::size_t j);
    // Dantzig's rule over the real columns; false when it does not settle.
    bool run(double give_up);

    std::size_t n_ = 0, rows_ = 0; // rows_ = n + 1: the z rows, then sum y = 1
    // Column-major tableau: the rows_ artificial columns (B^-1), then two a row; the right-hand
    // side and the reduced costs apart (d_rhs_: minus the objective, the bound on the fit).
    std::vector<double> col_, g_, d_, rhs_, entering_;
    std::vector<std::size_t> basis_;
    double d_rhs_ = 0.0;
    bool started_ = false; // phase 1 done: later rows join phase 2
};

} // namespace tinlod::erase
