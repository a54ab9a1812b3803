// The free-heights pass after the flip pass (free_heights.hpp).
#include "erase/free_heights.hpp"

#include "erase/hole_geometry.hpp"
#include "erase/ring_triangulation.hpp"
#include "erase/tin_arrays.hpp"
#include "lattice_triangle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tinlod::erase {

void BoxNarrowing::reset(const std::vector<double> &low, const std::vector<double> &high,
                         double limit) {
    low_ = low;
    high_ = high;
    limit_ = limit;
}

// The fit is min t subject to a_i . z - t <= b_i and -a_i . z - t <= -b_i. Its dual: min g . y over
// y >= 0 with sum_j y_j G_j = 0 on the z rows and sum_j y_j = 1, G_j = +-a_i, g_j = +-b_i; its
// optimum is -t*, and -g . y bounds t* from below on the way. Phase 1 starts from one artificial
// column per row; their columns hold B^-1 from then on, which is what a later row's columns need.
void ChebyshevFit::reset(int n) {
    n_ = std::size_t(n);
    rows_ = n_ + 1;
    col_.assign(rows_ * rows_, 0.0);
    for (std::size_t r = 0; r < rows_; ++r)
        col_[r * rows_ + r] = 1.0;
    g_.assign(rows_, 0.0);
    d_.assign(rows_, 0.0);
    rhs_.assign(rows_, 0.0);
    rhs_[n_] = 1.0;
    basis_.resize(rows_);
    for (std::size_t r = 0; r < rows_; ++r)
        basis_[r] = r;
    started_ = false;
}

void ChebyshevFit::add_row(const double *a, double b) {
    // The columns (a, 1) and (-a, 1): B^-1 times them is s + B^-1 e_n and -s + B^-1 e_n with s =
    // B^-1 (a, 0), summed once (a negated sum rounds as the sum negated), and likewise their
    // reduced costs.
    const std::size_t at = col_.size();
    col_.resize(at + 2 * rows_, 0.0);
    double *plus = &col_[at], *minus = plus + rows_;
    double d = b;
    for (std::size_t k = 0; k < n_; ++k) {
        if (a[k] == 0.0)
            continue;
        const double *inverse = &col_[k * rows_];
        for (std::size_t r = 0; r < rows_; ++r)
            plus[r] += a[k] * inverse[r];
        d += a[k] * d_[k];
    }
    const double *sum = &col_[n_ * rows_];
    for (std::size_t r = 0; r < rows_; ++r) {
        minus[r] = -plus[r] + sum[r];
        plus[r] += sum[r];
    }
    g_.push_back(b);
    g_.push_back(-b);
    d_.push_back(started_ ? d + d_[n_] : 0.0);
    d_.push_back(started_ ? -d + d_[n_] : 0.0);
}

void ChebyshevFit::pivot(std::size_t r, std::size_t j) {
    entering_.assign(col_.begin() + std::ptrdiff_t(j * rows_),
                     col_.begin() + std::ptrdiff_t((j + 1) * rows_));
    const double p = entering_[r], dj = d_[j];
    const auto update = [&](double *c, double &d) {
        const double x = c[r] / p;
        if (x == 0.0)
            return;
        for (std::size_t o = 0; o < rows_; ++o)
            c[o] -= entering_[o] * x;
        c[r] = x;
        d -= dj * x;
    };
    const std::size_t columns = g_.size();
    for (std::size_t c = 0; c < columns; ++c)
        update(&col_[c * rows_], d_[c]);
    update(rhs_.data(), d_rhs_);
    basis_[r] = j;
}

bool ChebyshevFit::run(double give_up) {
    const double eps = 1e-11;
    for (int it = 0; it < 50 * int(rows_) + 200; ++it) {
        if (d_rhs_ > give_up)
            return true;
        const std::size_t columns = g_.size();
        std::size_t j = columns;
        double most = -eps;
        for (std::size_t c = rows_; c < columns; ++c)
            if (d_[c] < most) {
                most = d_[c];
                j = c;
            }
        if (j == columns)
            return true;
        const double *e = &col_[j * rows_];
        std::size_t r = rows_;
        double ratio = INFINITY;
        for (std::size_t o = 0; o < rows_; ++o)
            if (e[o] > 1e-9) {
                const double q = rhs_[o] / e[o];
                if (q < ratio || (q == ratio && basis_[o] < basis_[r])) {
                    ratio = q;
                    r = o;
                }
            }
        if (r == rows_)
            return false; // unbounded: not for a feasible fit
        pivot(r, j);
    }
    return false;
}

double ChebyshevFit::solve(double give_up, std::vector<double> &z) {
    const std::size_t columns = g_.size();
    if (!started_) {
        // Phase 1: the artificials' sum, from reduced costs -sum_r T[r][c] on the real columns.
        for (std::size_t c = rows_; c < columns; ++c) {
            double s = 0.0;
            for (std::size_t r = 0; r < rows_; ++r)
                s -= col_[c * rows_ + r];
            d_[c] = s;
        }
        d_rhs_ = -1.0;
        if (!run(INFINITY) || d_rhs_ < -1e-9)
            return INFINITY;
        for (std::size_t r = 0; r < rows_; ++r) {
            if (basis_[r] >= rows_)
                continue;
            std::size_t j = columns;
            for (std::size_t c = rows_; c < columns && j == columns; ++c)
                if (std::abs(col_[c * rows_ + r]) > 1e-9)
                    j = c;
            if (j == columns)
                return INFINITY; // a redundant row: no variable is free to move
            pivot(r, j);
        }
        // Phase 2: d = g - g_B B^-1 A over every column (the artificials' cost 0).
        for (std::size_t c = 0; c < columns; ++c) {
            double s = g_[c];
            for (std::size_t r = 0; r < rows_; ++r)
                s -= g_[basis_[r]] * col_[c * rows_ + r];
            d_[c] = s;
        }
        d_rhs_ = 0.0;
        for (std::size_t r = 0; r < rows_; ++r)
            d_rhs_ -= g_[basis_[r]] * rhs_[r];
        started_ = true;
    }
    if (!run(give_up))
        return INFINITY;
    // The fit's z: the dual values of the z rows, minus the reduced costs of their artificials.
    z.resize(n_);
    for (std::size_t k = 0; k < n_; ++k)
        z[k] = -d_[k];
    return std::max(d_rhs_, 0.0);
}

namespace {

// A triangle of the try: its corner nodes and their variables (-1: a fixed height).
struct Corners {
    std::array<std::int32_t, 3> node;
    std::array<int, 3> var;
};

class Pass {
  public:
    Pass(TinArrays &tin, const Heightfield &hf, double limit, int max_ring)
        : tin_(tin), hf_(hf), limit_(limit), max_ring_(max_ring), changed_(tin.sample.size(), 0),
          tried_(tin.sample.size(), 0), kept_(tin.sample.size(), k_none) {}

    // Tries to erase the interior node v; on success rewrites the TIN and its heights, leaves the
    // nodes whose neighbourhood changed in touched() and returns true.
    bool erase(std::int32_t v) {
        if (tin_.outline[std::size_t(v)] || !gather(v))
            return false;
        const int n = int(ring_.size());
        const int count = hole(v, n);
        if (count != n - 2)
            return false;
        // The variables: the ring's interior nodes.
        vars_.clear();
        for (const std::int32_t r : ring_)
            if (!tin_.outline[std::size_t(r)])
                vars_.push_back(r);
        // The triangles whose planes move: the new ones, and those around a variable node but v's.
        tris_.clear();
        for (int j = 0; j < count; ++j)
            tris_.push_back(corners({ring_[tri_[std::size_t(j)].a], ring_[tri_[std::size_t(j)].b],
                                     ring_[tri_[std::size_t(j)].c]}));
        new_tris_ = tris_.size();
        around_.clear();
        for (const std::int32_t r : vars_) {
            std::int32_t t = tin_.fan[std::size_t(r)];
            const std::int32_t first = t;
            do {
                const int k = tin_.index_of(t, r);
                if (tin_.at(t, 0) != v && tin_.at(t, 1) != v && tin_.at(t, 2) != v)
                    around_.push_back(t);
                t = tin_.across[3 * std::size_t(t) + std::size_t((k + 2) % 3)];
            } while (t != first && t >= 0);
        }
        std::sort(around_.begin(), around_.end());
        around_.erase(std::unique(around_.begin(), around_.end()), around_.end());
        for (const std::int32_t t : around_)
            tris_.push_back(corners({tin_.at(t, 0), tin_.at(t, 1), tin_.at(t, 2)}));
        if (!fit()) {
            // In heights (not changes) the new triangles' rows depend on the ring alone: when they
            // rule the hole out, it stays ruled out while v's star stands.
            if (by_hole_)
                kept_[std::size_t(v)] = k_none;
            return false;
        }
        if (!holds()) {
            for (std::size_t k = 0; k < vars_.size(); ++k)
                tin_.z[std::size_t(vars_[k])] = old_z_[k];
            return false;
        }
        rewrite(v, count);
        // The ring's stars changed (and the variables' heights).
        ++epoch_;
        for (const std::int32_t r : ring_)
            changed_[std::size_t(r)] = epoch_;
        touched_.clear();
        for (const Corners &c : tris_)
            touched_.insert(touched_.end(), c.node.begin(), c.node.end());
        return true;
    }

    const std::vector<std::int32_t> &touched() const { return touched_; }

  private:
    bool gather(std::int32_t v) { return tin_.star(v, max_ring_, ring_, star_, edge_); }

    // v's hole (its ring of n nodes) triangulated into tri_: the triangulation that keeps its
    // samples farthest within reach of the limit; its count, or -1 when v's own sample or the
    // hole's samples are out of reach. It depends on the ring alone: a node tried again after a
    // neighbour's erase whose star has not changed since gets its last try's.
    int hole(std::int32_t v, int n) {
        const std::size_t i = std::size_t(v);
        if (tried_[i] != 0 && changed_[i] <= tried_[i]) {
            if (kept_[i] == k_none)
                return -1;
            std::copy_n(kept_tri_.begin() + std::ptrdiff_t(kept_[i]), n - 2, tri_.begin());
            return n - 2;
        }
        tried_[i] = epoch_;
        kept_[i] = k_none;
        for (int k = 0; k < n; ++k)
            q_[std::size_t(k)] = {double(tin_.col[std::size_t(ring_[std::size_t(k)])]),
                                  double(tin_.row[std::size_t(ring_[std::size_t(k)])])};
        own_x_ = tin_.col[i];
        own_y_ = tin_.row[i];
        if (!within_reach())
            return -1;
        const int count = min_max_triangulation(
            q_.data(), n, limit_,
            [this](int a, int b, int c, double stop) {
                return reach({ring_[std::size_t(a)], ring_[std::size_t(b)], ring_[std::size_t(c)]},
                             stop);
            },
            tri_.data());
        if (count == n - 2) {
            kept_[i] = std::uint32_t(kept_tri_.size());
            kept_tri_.insert(kept_tri_.end(), tri_.begin(), tri_.begin() + count);
        }
        return count;
    }

    Corners corners(std::array<std::int32_t, 3> node) const {
        Corners c{node, {-1, -1, -1}};
        for (int k = 0; k < 3; ++k) {
            const auto it = std::find(vars_.begin(), vars_.end(), node[std::size_t(k)]);
            if (it != vars_.end())
                c.var[std::size_t(k)] = int(it - vars_.begin());
        }
        return c;
    }

    // The lattice columns x and rows y of nodes c.
    void cells(const std::array<std::int32_t, 3> &c, std::int64_t (&x)[3],
               std::int64_t (&y)[3]) const {
        for (std::size_t k = 0; k < 3; ++k) {
            x[k] = tin_.col[std::size_t(c[k])];
            y[k] = tin_.row[std::size_t(c[k])];
        }
    }

    // The samples of the closed lattice triangle over nodes c (counter-clockwise) but its corners:
    // visit(x, y, sa, sb, sc), with sa, sb, sc the doubled lattice areas that weigh the corners
    // (their sum: twice the triangle's area); false when a visit stopped the scan. A small triangle
    // over its box, a larger one a row span at a time, its areas stepped along the row (exact
    // integers), the corners looked for on their rows alone: in the order of the box either way.
    template <class Visit>
    bool scan(const std::array<std::int32_t, 3> &c, const Visit &visit) const {
        std::int64_t x[3], y[3];
        cells(c, x, y);
        const auto corner = [&](std::int64_t px, std::int64_t py) {
            return (px == x[0] && py == y[0]) || (px == x[1] && py == y[1]) ||
                   (px == x[2] && py == y[2]);
        };
        // Corner k's doubled area at (px, py): that of the triangle (px, py), corner k + 1, k + 2.
        const auto area = [&](int k, std::int64_t px, std::int64_t py) {
            const int a = (k + 1) % 3, b = (k + 2) % 3;
            return (x[a] - px) * (y[b] - py) - (y[a] - py) * (x[b] - px);
        };
        if (box_samples(x, y) <= k_small_box)
            return visit_box(x, y, [&](std::int64_t px, std::int64_t py) {
                return corner(px, py) || visit(px, py, double(area(0, px, py)),
                                               double(area(1, px, py)), double(area(2, px, py)));
            });
        const std::int64_t step[3] = {y[1] - y[2], y[2] - y[0], y[0] - y[1]};
        return LatticeTriangle(x, y).for_each_row([&](std::int64_t py, std::int64_t lo,
                                                      std::int64_t hi) {
            std::int64_t sa = area(0, lo, py), sb = area(1, lo, py), sc = area(2, lo, py);
            const bool corners = py == y[0] || py == y[1] || py == y[2];
            for (std::int64_t px = lo; px <= hi; ++px, sa += step[0], sb += step[1], sc += step[2])
                if (!(corners && corner(px, py)) &&
                    !visit(px, py, double(sa), double(sb), double(sc)))
                    return false;
            return true;
        });
    }

    // Whether v's sample is within reach (reach) of some triangle over three ring nodes whose
    // closed lattice triangle holds it: else no triangulation of the hole can keep it (most of
    // the nodes fail here, at a few operations each).
    bool within_reach() const {
        const std::size_t n = ring_.size();
        const double z = double(hf_.at(int(own_x_), int(own_y_)));
        std::array<std::int64_t, k_max_ring> rx, ry;
        std::array<double, k_max_ring> lo, hi;
        double low = INFINITY, high = -INFINITY;
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t u = std::size_t(ring_[i]);
            rx[i] = tin_.col[u] - own_x_;
            ry[i] = tin_.row[u] - own_y_;
            const double h = double(hf_.at(tin_.col[u], tin_.row[u])),
                         m = tin_.outline[u] ? 0.0 : limit_;
            lo[i] = h - m - limit_;
            hi[i] = h + m + limit_;
            low = std::min(low, lo[i]);
            high = std::max(high, hi[i]);
        }
        if (z < low || z > high)
            return false;
        for (std::size_t a = 0; a < n; ++a)
            for (std::size_t b = a + 1; b < n; ++b) {
                const std::int64_t s0 = rx[a] * ry[b] - ry[a] * rx[b];
                if (s0 < 0)
                    continue;
                for (std::size_t c = b + 1; c < n; ++c) {
                    const std::int64_t s1 = rx[b] * ry[c] - ry[b] * rx[c],
                                       s2 = rx[c] * ry[a] - ry[c] * rx[a];
                    if (s1 < 0 || s2 < 0 || s0 + s1 + s2 <= 0)
                        continue;
                    // Weights: s1 on a, s2 on b, s0 on c.
                    const double area = double(s0 + s1 + s2);
                    if (z * area >= lo[a] * double(s1) + lo[b] * double(s2) + lo[c] * double(s0) &&
                        z * area <= hi[a] * double(s1) + hi[b] * double(s2) + hi[c] * double(s0))
                        return true;
                }
            }
        return false;
    }

    // How far the samples of the triangle over nodes c miss the limit with each interior corner
    // moved as far as its own sample lets it: the largest of |h - p| - limit * m over them, p the
    // plane through the corners' samples at the sample, m the weight of the corners that may move
    // (the outline's stay). Over the limit, no heights keep the sample within it. Exactly up to
    // `stop`, beyond it some value over it; v's sample (the one most often out of reach) first.
    double reach(const std::array<std::int32_t, 3> &c, double stop) const {
        std::array<double, 3> h, free;
        std::int64_t x[3], y[3];
        for (int k = 0; k < 3; ++k) {
            const std::size_t u = std::size_t(c[std::size_t(k)]);
            x[k] = tin_.col[u];
            y[k] = tin_.row[u];
            h[std::size_t(k)] = double(hf_.at(tin_.col[u], tin_.row[u]));
            free[std::size_t(k)] = tin_.outline[u] ? 0.0 : limit_;
        }
        const auto miss = [&](std::int64_t px, std::int64_t py, double sa, double sb, double sc) {
            const double area = sa + sb + sc;
            const double p = (sa * h[0] + sb * h[1] + sc * h[2]) / area,
                         m = (sa * free[0] + sb * free[1] + sc * free[2]) / area;
            return std::abs(double(hf_.at(int(px), int(py))) - p) - m;
        };
        const std::int64_t sa = (x[1] - own_x_) * (y[2] - own_y_) -
                                (y[1] - own_y_) * (x[2] - own_x_),
                           sb = (x[2] - own_x_) * (y[0] - own_y_) -
                                (y[2] - own_y_) * (x[0] - own_x_),
                           sc = (x[0] - own_x_) * (y[1] - own_y_) -
                                (y[0] - own_y_) * (x[1] - own_x_);
        double most = 0.0;
        if (sa >= 0 && sb >= 0 && sc >= 0) {
            most = miss(own_x_, own_y_, double(sa), double(sb), double(sc));
            if (most > stop)
                return most;
        }
        if (box_samples(x, y) <= k_small_box) {
            scan(c, [&](std::int64_t px, std::int64_t py, double wa, double wb, double wc) {
                most = std::max(most, miss(px, py, wa, wb, wc));
                return most <= stop;
            });
            return most;
        }
        // A larger triangle: the planes through the corners' samples raised and lowered by their
        // room, stepped, pass over the samples that cannot raise the largest miss by k_near;
        // miss() gives the others exactly, in scan()'s order.
        std::array<double, 3> raised, lowered;
        for (std::size_t k = 0; k < 3; ++k) {
            raised[k] = h[k] + free[k];
            lowered[k] = h[k] - free[k];
        }
        double ceiling = most - k_near, floor = -ceiling;
        scan_stepped(hf_, x, y, raised, lowered, floor, ceiling,
                     [&](std::int64_t px, std::int64_t py, double wa, double wb, double wc) {
                         most = std::max(most, miss(px, py, wa, wb, wc));
                         ceiling = most - k_near;
                         floor = -ceiling;
                         return most <= stop;
                     });
        return most;
    }

    // One row of the programme: |sum_k w[k] dz[var[k]] - r| <= limit (var -1: none), and how far
    // the variables' boxes reach past it.
    struct Row {
        std::array<int, 3> var;
        std::array<double, 3> w;
        double r, excess;
        double miss(const std::vector<double> &dz) const {
            double s = -r;
            for (int k = 0; k < 3; ++k)
                if (var[std::size_t(k)] >= 0)
                    s += w[std::size_t(k)] * dz[std::size_t(var[std::size_t(k)])];
            return std::abs(s);
        }
    };

    // The linear programme over the variables' height changes: each sample of tris_ (and each
    // variable node's own sample) within the limit of the plane over it. Sets the heights it finds
    // (as floats), keeping the old ones in old_z_; false when none keeps within the limit.
    bool fit() {
        const std::size_t nv = vars_.size();
        rows_.clear();
        by_hole_ = true;
        double fixed = 0.0; // the largest deviation no variable changes
        // Each variable's own sample keeps its change within [low, high]: a row whose weighted
        // range misses its own [r - limit, r + limit] rules the erase out before the programme.
        low_.resize(nv);
        high_.resize(nv);
        for (std::size_t k = 0; k < nv; ++k) {
            const std::size_t s = std::size_t(vars_[k]);
            const double off = double(hf_.at(tin_.col[s], tin_.row[s])) - tin_.z[s];
            low_[k] = off - limit_;
            high_[k] = off + limit_;
            rows_.push_back({{int(k), -1, -1}, {1.0, 0.0, 0.0}, off, INFINITY});
        }
        boxes_.reset(low_, high_, limit_);
        std::size_t new_rows = rows_.size();
        for (std::size_t t = 0; t < tris_.size(); ++t) {
            if (t == new_tris_) {
                new_rows = rows_.size();
                by_hole_ = false;
            }
            const Corners &c = tris_[t];
            const double za = tin_.z[std::size_t(c.node[0])], zb = tin_.z[std::size_t(c.node[1])],
                         zc = tin_.z[std::size_t(c.node[2])];
            const bool moves = c.var[0] >= 0 || c.var[1] >= 0 || c.var[2] >= 0;
            const auto exact = [&](std::int64_t x, std::int64_t y, double sa, double sb,
                                   double sc) {
                const double area = sa + sb + sc;
                const double r =
                    double(hf_.at(int(x), int(y))) - (sa * za + sb * zb + sc * zc) / area;
                if (!moves) {
                    fixed = std::max(fixed, std::abs(r));
                    return fixed <= limit_;
                }
                Row row{c.var, {sa / area, sb / area, sc / area}, r, 0.0};
                double lo = 0.0, hi = 0.0;
                for (std::size_t k = 0; k < 3; ++k)
                    if (row.var[k] >= 0) {
                        lo += row.w[k] * low_[std::size_t(row.var[k])];
                        hi += row.w[k] * high_[std::size_t(row.var[k])];
                    }
                if (lo > r + limit_ || hi < r - limit_)
                    return false;
                // A row the box keeps within the limit needs no place in the programme: a fit
                // within the limit keeps every variable in its box.
                if (lo >= r - limit_ && hi <= r + limit_)
                    return true;
                row.excess = std::max(hi - r, r - lo);
                rows_.push_back(row);
                // Each row narrows the boxes as it comes: they rule out most holes the
                // programme would, most of them before the scan ends, and decide nothing else
                // (the programmes see the same rows and find the same heights).
                return boxes_.add(row.var, row.w, row.r) && rows_.size() <= k_max_rows;
            };
            std::int64_t x[3], y[3];
            cells(c.node, x, y);
            // A larger triangle: the planes through its corners at the lowest and the highest
            // heights their boxes let them take (a fixed corner at its own) tell the samples whose
            // residual both keep within the limit by k_near, which exact() would pass over (in a
            // fixed triangle the two are one: the samples within the limit of it).
            bool ok;
            if (box_samples(x, y) <= k_small_box) {
                ok = scan(c.node, exact);
            } else {
                std::array<double, 3> down, up;
                for (std::size_t k = 0; k < 3; ++k) {
                    const double z = tin_.z[std::size_t(c.node[k])];
                    down[k] = c.var[k] >= 0 ? z + low_[std::size_t(c.var[k])] : z;
                    up[k] = c.var[k] >= 0 ? z + high_[std::size_t(c.var[k])] : z;
                }
                ok = scan_stepped(hf_, x, y, down, up, -limit_ + k_near, limit_ - k_near, exact);
            }
            if (!ok)
                return false;
        }
        old_z_.resize(nv);
        for (std::size_t k = 0; k < nv; ++k)
            old_z_[k] = tin_.z[std::size_t(vars_[k])];
        if (nv == 0)
            return true;
        // A second sweep of the narrowing, each row against the boxes all the others left (a
        // third, or the rows in reverse, cost more than they save).
        for (const Row &row : rows_)
            if (!boxes_.add(row.var, row.w, row.r))
                return false;
        // The programme on the new triangles' rows first, then on all.
        const bool around = new_tris_ < tris_.size();
        by_hole_ = true;
        if (around && !solve(nv, new_rows, true))
            return false;
        by_hole_ = !around;
        if (!solve(nv, rows_.size(), !around))
            return false;
        for (std::size_t k = 0; k < nv; ++k)
            tin_.z[std::size_t(vars_[k])] = double(float(old_z_[k] + dz_[k]));
        return true;
    }

    // Heights within the limit of the first m rows_ in dz_: the programme on the rows whose boxes'
    // reach most exceeds the limit (the variables' own rows first), then with the rows its fit
    // misses, until it misses none (the fit rests on about as many rows as variables, of up to
    // thousands at a coarse bound). `fresh`: a new programme; else the last one's, with the rows
    // added since. False when a programme on some of the rows finds none.
    bool solve(std::size_t nv, std::size_t m, bool fresh) {
        if (fresh) {
            const std::size_t first = std::min(m, 3 * nv + 4);
            std::nth_element(rows_.begin(), rows_.begin() + std::ptrdiff_t(first - 1),
                             rows_.begin() + std::ptrdiff_t(m),
                             [](const Row &i, const Row &j) { return i.excess > j.excess; });
            picked_.assign(m, 0);
            fit_.reset(int(nv));
            for (std::size_t i = 0; i < first; ++i)
                add(i, nv);
        } else {
            picked_.resize(m, 0);
        }
        for (int round = 0; round < 32; ++round) {
            if (fresh || round > 0) {
                if (!(fit_.solve(limit_, dz_) <= limit_))
                    return false;
            }
            bool missed = false;
            for (std::size_t i = 0; i < m; ++i)
                if (!picked_[i] && rows_[i].miss(dz_) > limit_) {
                    add(i, nv);
                    missed = true;
                }
            if (!missed)
                return true;
        }
        return false;
    }

    // Adds row i to the programme.
    void add(std::size_t i, std::size_t nv) {
        picked_[i] = 1;
        dense_.assign(nv, 0.0);
        for (std::size_t k = 0; k < 3; ++k)
            if (rows_[i].var[k] >= 0)
                dense_[std::size_t(rows_[i].var[k])] += rows_[i].w[k];
        fit_.add_row(dense_.data(), rows_[i].r);
    }

    // Whether every sample of tris_ (corners included) lies within the limit of the triangle over
    // it at the heights set, as the erase measures (the flip pass's cost): the plane's rounding
    // margin at each sample, and at the corners the margin a steep triangle's float corner needs.
    bool holds() const {
        for (const Corners &c : tris_) {
            std::array<glm::dvec3, 3> p;
            for (int k = 0; k < 3; ++k) {
                const std::size_t s = std::size_t(c.node[std::size_t(k)]);
                const Mesh::Point g = grid_point(hf_, tin_.col[s], tin_.row[s]);
                p[std::size_t(k)] = {double(g[0]), double(g[1]), tin_.z[s]};
            }
            const TrianglePlane plane(p[0], p[1], p[2]);
            const double margin = plane.margin_over(p[0], p[1], p[2]);
            for (int k = 0; k < 3; ++k) {
                const std::size_t s = std::size_t(c.node[std::size_t(k)]);
                const glm::dvec3 &q = p[std::size_t(k)];
                const double h = double(hf_.at(tin_.col[s], tin_.row[s]));
                if (std::max(rounding_margin(std::max(std::abs(q.x), std::abs(q.y)), plane.slope()),
                             plane.deviation(q.x, q.y, h, margin)) > limit_)
                    return false;
            }
            const auto exact = [&](std::int64_t x, std::int64_t y, double, double, double) {
                const Mesh::Point g = grid_point(hf_, int(x), int(y));
                return plane.deviation(g[0], g[1], g[2], margin) <= limit_;
            };
            std::int64_t x[3], y[3];
            cells(c.node, x, y);
            if (box_samples(x, y) <= k_small_box) {
                if (!scan(c.node, exact))
                    return false;
                continue;
            }
            // A larger triangle: its plane in lattice units passes over the samples within the
            // limit by more than the steps' rounding and what the float coordinates (grid_point)
            // move the plane by (the slope times their rounding).
            const double coord = std::max({std::abs(p[0].x), std::abs(p[0].y), std::abs(p[1].x),
                                           std::abs(p[1].y), std::abs(p[2].x), std::abs(p[2].y)});
            const double sure = limit_ - margin - k_near - 4.0 * plane.slope() * coord * 0x1p-24;
            const std::array<double, 3> z = {p[0].z, p[1].z, p[2].z};
            if (!scan_stepped(hf_, x, y, z, z, -sure, sure, exact))
                return false;
        }
        return true;
    }

    // Replaces v's star by the new triangles tri_ over its ring.
    void rewrite(std::int32_t v, int count) {
        const std::size_t n = ring_.size();
        // The triangle outside each ring edge ring[i] -> ring[i + 1] (-1 on the outline).
        outside_.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            outside_[i] = tin_.across[3 * std::size_t(star_[i]) + std::size_t(edge_[i])];
        tin_.fan[std::size_t(v)] = -1;
        for (std::size_t i = std::size_t(count); i < n; ++i)
            tin_.corner[3 * std::size_t(star_[i])] = -1;
        for (int j = 0; j < count; ++j) {
            const std::int32_t t = star_[std::size_t(j)];
            const std::uint8_t c[3] = {tri_[std::size_t(j)].a, tri_[std::size_t(j)].b,
                                       tri_[std::size_t(j)].c};
            for (int k = 0; k < 3; ++k) {
                tin_.corner[3 * std::size_t(t) + std::size_t(k)] = ring_[c[k]];
                tin_.fan[std::size_t(ring_[c[k]])] = t;
            }
        }
        for (int j = 0; j < count; ++j) {
            const std::int32_t t = star_[std::size_t(j)];
            const std::uint8_t c[3] = {tri_[std::size_t(j)].a, tri_[std::size_t(j)].b,
                                       tri_[std::size_t(j)].c};
            for (int k = 0; k < 3; ++k) {
                const std::uint8_t a = c[k], b = c[(k + 1) % 3];
                std::int32_t &link = tin_.across[3 * std::size_t(t) + std::size_t(k)];
                if (std::size_t(b) == (std::size_t(a) + 1) % n) {
                    link = outside_[a];
                    if (link >= 0)
                        tin_.across[3 * std::size_t(link) +
                                    std::size_t(tin_.index_of(link, ring_[b]))] = t;
                    continue;
                }
                for (int o = 0; o < count; ++o) {
                    const std::uint8_t d[3] = {tri_[std::size_t(o)].a, tri_[std::size_t(o)].b,
                                               tri_[std::size_t(o)].c};
                    for (int e = 0; e < 3; ++e)
                        if (d[e] == b && d[(e + 1) % 3] == a)
                            link = star_[std::size_t(o)];
                }
            }
        }
    }

    // How far a value stepped along a row may be off the one computed at its sample (metres: far
    // over the steps' rounding, far under a limit).
    static constexpr double k_near = 1e-6;
    // A linear programme over more samples than this is not tried (coarse bounds' large holes).
    static constexpr std::size_t k_max_rows = 4096;

    TinArrays &tin_;
    const Heightfield &hf_;
    const double limit_;
    const int max_ring_;
    std::vector<std::int32_t> ring_, star_, vars_, around_, outside_, touched_;
    std::vector<int> edge_;
    std::array<glm::dvec2, k_max_ring> q_;
    std::array<RingTriangle, k_max_ring> tri_;
    std::vector<Corners> tris_;
    std::vector<Row> rows_;
    std::size_t new_tris_ = 0;
    bool by_hole_ = false; // the last fit() was ruled out by the new triangles' rows alone
    std::vector<double> dense_, dz_, old_z_, low_, high_;
    BoxNarrowing boxes_;
    std::vector<std::uint8_t> picked_;
    ChebyshevFit fit_;
    std::int64_t own_x_ = 0, own_y_ = 0;
    // Per node: the erase after which its star last changed, and the erases before its last
    // hole() (0: none yet; the pass's count of erases from 1); the hole it found then (its
    // triangles' first in kept_tri_, k_none when none).
    std::uint32_t epoch_ = 1;
    std::vector<std::uint32_t> changed_, tried_, kept_;
    std::vector<RingTriangle> kept_tri_;
    static constexpr std::uint32_t k_none = 0xffffffffu;
};

} // namespace

Mesh free_heights(const Mesh &mesh, const Heightfield &hf, double limit, int max_valence,
                  FreeHeightsStats *stats) {
    TinArrays tin = tin_arrays(mesh, hf);
    Pass pass(tin, hf, limit, std::min(max_valence, k_max_ring));
    FreeHeightsStats out;
    // The nodes near each erase are tried again.
    const std::vector<std::int32_t> none;
    until_none_goes(tin.sample.size(), [&](std::int32_t v) -> const std::vector<std::int32_t> & {
        if (!pass.erase(v))
            return none;
        ++out.erased;
        return pass.touched();
    });
    Mesh left = nodes_left(tin, mesh);
    if (stats)
        *stats = out;
    return left;
}

} // namespace tinlod::erase
