// The erase's last pass at a vertical bound (flip_pass.hpp).
#include "erase/flip_pass.hpp"

#include "erase/hole_geometry.hpp"
#include "erase/ring_triangulation.hpp"
#include "erase/tin_arrays.hpp"
#include "lattice_triangle.hpp"
#include "tinlod/significance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace tinlod::erase {

bool flip_pass_applies(const Significance &model, const EraseOptions &options) {
    return model.model() == SpModel::vertical && std::isfinite(options.tolerance) &&
           options.tolerance > 0.0 && options.max_nodes <= 0;
}

namespace {

// Whether height z lies within `stop` of the plane over corner heights za, zb, zc at a point
// whose doubled lattice areas against the sides (a, b), (b, c), (c, a) are s0, s1, s2 (each >= 0,
// their sum > 0): the plane's height from its exact barycentric weights, as the erase's
// over_every_triangle has it, times the area (no division).
// The areas come as doubles (exact: lattice areas are far under 2^53), converted once per pair.
bool near_plane(double s0, double s1, double s2, double za, double zb, double zc, double z,
                double stop) {
    const double area = s0 + s1 + s2;
    return std::abs(z * area - (za * s1 + zb * s2 + zc * s0)) <= stop * area;
}

// side[a][b]: twice the signed area of (node a, node b, the sample), lattice units, from the nodes'
// columns rx and rows ry relative to the sample's; once per pair, as doubles (exact: lattice areas
// are far under 2^53).
using SideAreas = std::array<std::array<double, k_max_ring>, k_max_ring>;
void side_areas(const std::array<std::int64_t, k_max_ring> &rx,
                const std::array<std::int64_t, k_max_ring> &ry, std::size_t n, SideAreas &side) {
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = a + 1; b < n; ++b) {
            side[a][b] = double(rx[a] * ry[b] - ry[a] * rx[b]);
            side[b][a] = -side[a][b];
        }
}

// The height at the sample (the origin) of the plane through the points t at heights
// sign * (h - z).
double plane_at(const std::int64_t *x, const std::int64_t *y, const double *h, double z,
                double sign, const int t[3]) {
    const auto cross = [&](int a, int b) { return double(x[a] * y[b] - y[a] * x[b]); };
    const double s0 = cross(t[0], t[1]), s1 = cross(t[1], t[2]), s2 = cross(t[2], t[0]);
    return (sign * (h[t[0]] - z) * s1 + sign * (h[t[1]] - z) * s2 + sign * (h[t[2]] - z) * s0) /
           (s0 + s1 + s2);
}

// One side of cover_ruled_out from the triangle t that holds the sample (heights d = sign *
// (h - z)): whether a plane over every point is under -stop there, a rounding margin under.
// Leaves in t the walk's last triangle.
bool planes_under(const std::int64_t *x, const std::int64_t *y, const double *h, int n, double z,
                  double stop, double sign, int t[3]) {
    const auto d = [&](int i) { return sign * (h[i] - z); };
    const auto cross = [&](int a, int b) { return x[a] * y[b] - y[a] * x[b]; };
    const auto holds = [&](int a, int b, int c) {
        const std::int64_t s0 = cross(a, b), s1 = cross(b, c), s2 = cross(c, a);
        return s0 >= 0 && s1 >= 0 && s2 >= 0 && s0 + s1 + s2 > 0;
    };
    // Each step's triangle holds the sample, its plane there no lower than the last's (the point
    // farthest over the plane replaces a corner): the walk ends at the upper hull's facet.
    for (int step = 0; step < 2 * n + 4; ++step) {
        if (!(plane_at(x, y, h, z, sign, t) < -stop))
            return false; // a triangle that holds the sample may cover it
        // The plane's slope: d = at + alpha * x + beta * y through the three corners.
        const double x1 = double(x[t[1]] - x[t[0]]), y1 = double(y[t[1]] - y[t[0]]),
                     x2 = double(x[t[2]] - x[t[0]]), y2 = double(y[t[2]] - y[t[0]]),
                     d1 = d(t[1]) - d(t[0]), d2 = d(t[2]) - d(t[0]), det = x1 * y2 - x2 * y1;
        const double alpha = (d1 * y2 - d2 * y1) / det, beta = (x1 * d2 - x2 * d1) / det;
        // over: the plane with that slope over every point, its height at the sample.
        double over = -INFINITY;
        int far = -1;
        for (int i = 0; i < n; ++i) {
            const double top = d(i) - alpha * double(x[i]) - beta * double(y[i]);
            if (top > over) {
                over = top;
                far = i;
            }
        }
        if (over < -stop) {
            // The margin bounds the rounding of `over` and of near_plane's test (measured only
            // here: most walks end before).
            double slack = std::abs(z) + stop, mx = 0.0, my = 0.0;
            for (int i = 0; i < n; ++i) {
                slack = std::max(slack, std::abs(h[i]) + std::abs(z) + stop);
                mx = std::max(mx, std::abs(double(x[i])));
                my = std::max(my, std::abs(double(y[i])));
            }
            return over < -stop - 1e-9 * (slack + std::abs(alpha) * mx + std::abs(beta) * my);
        }
        if (far == t[0] || far == t[1] || far == t[2])
            return false;
        if (holds(far, t[1], t[2]))
            t[0] = far;
        else if (holds(t[0], far, t[2]))
            t[1] = far;
        else if (holds(t[0], t[1], far))
            t[2] = far;
        else
            return false;
    }
    return false;
}

} // namespace

bool cover_ruled_out(const std::int64_t *x, const std::int64_t *y, const double *h, int n, double z,
                     double stop, int start[3]) {
    const double at = plane_at(x, y, h, z, 1.0, start);
    // The start's plane under z - stop: only an upper hull can keep every plane under; over z +
    // stop, only a lower one over.
    if (at < -stop)
        return planes_under(x, y, h, n, z, stop, 1.0, start);
    if (at > stop)
        return planes_under(x, y, h, n, z, stop, -1.0, start);
    return false;
}

namespace {

// A triple of polygon indices a < b < c.
struct Triple {
    std::uint8_t a, b, c;
};

// The pass's state: the TIN, the lattice, and the scratch of one node's try.
class Pass {
  public:
    Pass(TinArrays &tin, const Heightfield &hf, double limit, int max_ring)
        : tin_(tin), hf_(hf), limit_(limit), max_ring_(max_ring) {}

    // Tries to erase `v` (an interior node) with its hole widened by the triangle across each ring
    // edge (a flip of that edge towards v, then v's erase). Right after the erase (`first`) only
    // when v's own sample rules out every triangulation of its hole (coverable): a new corner may
    // give that sample a plane, where a node the erase failed on other samples still has them in
    // its hole (trying those too took twice the time for a few more erases). Once its ring
    // changed, its hole as it is first. On success rewrites the TIN, leaves the hole's outline in
    // outline() and returns 1, or 2 when the hole was widened; 0 when v stays.
    int erase(std::int32_t v, bool first) {
        if (!gather(v))
            return 0;
        own_node_ = std::size_t(v);
        own_ = tin_.sample[own_node_];
        witnesses_ = 0;
        add_witness(own_);
        extra_.clear();
        side_nodes_ = nullptr;
        const int n = int(ring_.size());
        ring_start();
        const bool held = coverable(ring_);
        if (held && first)
            return 0; // the erase failed this hole on other samples than v's
        if (held && n <= max_ring_ && triangulate(ring_))
            return 1;
        wide_.clear();
        // The widened polygon's walk goes on from the ring's last triangle (left in start_).
        const int ring_at[3] = {start_[0], start_[1], start_[2]};
        for (int i = 0; i < n; ++i) {
            const std::int32_t a = ring_[std::size_t(i)];
            for (int k = 0; k < 3; ++k)
                if (ring_at[k] == i)
                    start_[k] = int(wide_.size());
            wide_.push_back(a);
            const std::int32_t u =
                tin_.across[std::size_t(3 * star_[std::size_t(i)] + edge_[std::size_t(i)])];
            if (u < 0 || int(wide_.size()) + n - i > max_ring_)
                continue;
            // u is (b, a, d) counter-clockwise.
            const std::int32_t d = tin_.corner[std::size_t(3 * u + (tin_.index_of(u, a) + 1) % 3)];
            if (std::find(ring_.begin(), ring_.end(), d) != ring_.end() ||
                std::find(wide_.begin(), wide_.end(), d) != wide_.end())
                continue; // the outline would touch itself
            wide_.push_back(d);
            extra_.push_back(u);
        }
        // A triple of ring nodes that covers v's sample is one of the widened polygon's too (in
        // the same order).
        return !extra_.empty() && (held || coverable(wide_)) && triangulate(wide_) ? 2 : 0;
    }

    const std::vector<std::int32_t> &outline() const { return outline_; }

  private:
    bool gather(std::int32_t v) { return tin_.star(v, k_max_ring, ring_, star_, edge_); }

    // start_: three ring indices whose closed triangle holds v's sample, for cover_ruled_out: node
    // 0, the last of the nodes after it less than a half-turn on, the next (the ring goes around
    // v); -1 when that triangle does not hold it.
    void ring_start() {
        const std::size_t n = ring_.size();
        const std::int64_t xs = tin_.col[own_node_], ys = tin_.row[own_node_];
        const auto x = [&](std::size_t i) { return tin_.col[std::size_t(ring_[i])] - xs; };
        const auto y = [&](std::size_t i) { return tin_.row[std::size_t(ring_[i])] - ys; };
        const auto cross = [&](std::size_t a, std::size_t b) { return x(a) * y(b) - y(a) * x(b); };
        std::size_t b = 1;
        while (b + 1 < n && cross(0, b + 1) > 0)
            ++b;
        start_[0] = -1;
        if (b + 1 < n && cross(0, b) >= 0 && cross(b, b + 1) >= 0 && cross(b + 1, 0) >= 0 &&
            cross(0, b) + cross(b, b + 1) + cross(b + 1, 0) > 0) {
            start_[0] = 0;
            start_[1] = int(b);
            start_[2] = int(b + 1);
        }
    }

    // Whether v's sample lies within the limit (a hair over counts) of some triangle over three of
    // the polygon's nodes (counter-clockwise) whose closed lattice triangle holds it: else no
    // triangulation of the polygon holds the bound (most of the nodes the erase leaves fail here).
    // Leaves the polygon's side areas and the first such triangle for covered to go on from.
    bool coverable(const std::vector<std::int32_t> &nodes) {
        const std::size_t n = nodes.size();
        const double z = tin_.z[own_node_];
        const double stop = limit_ * (1.0 + 1e-9) + 1e-12 * std::abs(z);
        double lo = INFINITY, hi = -INFINITY;
        for (std::size_t i = 0; i < n; ++i) {
            side_z_[i] = tin_.z[std::size_t(nodes[i])];
            lo = std::min(lo, side_z_[i]);
            hi = std::max(hi, side_z_[i]);
        }
        // A plane over three nodes lies within their heights: a peak or a pit the nodes do not
        // reach within the limit stays (most of the nodes left at a fine bound).
        if (z - hi > stop || lo - z > stop)
            return false;
        // Most nodes left stand over (or under) every plane their polygon's triangles can give
        // them: a few steps of a walk towards the hull show it, where the triples cost O(n^3).
        load_offsets(nodes);
        if (start_[0] >= 0 &&
            cover_ruled_out(rx_.data(), ry_.data(), side_z_.data(), int(n), z, stop, start_))
            return false;
        side_areas(rx_, ry_, n, side_);
        side_nodes_ = &nodes;
        return near_triples(n, {0, 1, 2}, [&](std::size_t a, std::size_t b, std::size_t c) {
            from_ = {std::uint8_t(a), std::uint8_t(b), std::uint8_t(c)};
            return true;
        });
    }

    // rx_, ry_: the columns and rows of the polygon `nodes` relative to v's sample.
    void load_offsets(const std::vector<std::int32_t> &nodes) {
        const std::int64_t xs = tin_.col[own_node_], ys = tin_.row[own_node_];
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            rx_[i] = tin_.col[std::size_t(nodes[i])] - xs;
            ry_[i] = tin_.row[std::size_t(nodes[i])] - ys;
        }
    }

    // Calls visit(a, b, c) on each triple a < b < c of the polygon in side_ from `from` on, in
    // lexicographic order, whose closed lattice triangle holds v's sample with v's height within
    // the limit (a hair over counts) of their plane over the heights side_z_ (near_plane), until a
    // visit returns true; returns whether one did.
    template <class Visit> bool near_triples(std::size_t n, Triple from, Visit &&visit) const {
        const double z = tin_.z[own_node_];
        const double stop = limit_ * (1.0 + 1e-9) + 1e-12 * std::abs(z);
        const SideAreas &side = side_;
        const std::array<double, k_max_ring> &rz = side_z_;
        std::size_t b = from.b, c = from.c;
        for (std::size_t a = from.a; a < n; ++a, b = a + 1, c = b + 1)
            for (; b < n; ++b, c = b + 1) {
                if (side[a][b] < 0.0)
                    continue;
                for (; c < n; ++c) {
                    const double s0 = side[a][b], s1 = side[b][c], s2 = side[c][a];
                    if (s1 < 0.0 || s2 < 0.0 || s0 + s1 + s2 <= 0.0)
                        continue;
                    if (near_plane(s0, s1, s2, rz[a], rz[b], rz[c], z, stop) && visit(a, b, c))
                        return true;
                }
            }
        return false;
    }

    glm::dvec3 point(std::uint32_t sample) const {
        const int w = hf_.width;
        const Mesh::Point p = grid_point(hf_, int(sample % std::uint32_t(w)), int(sample / w));
        return to_glm(p);
    }

    void add_witness(std::uint32_t sample) {
        witness_[std::size_t(next_witness_)] = sample;
        next_witness_ = (next_witness_ + 1) % int(witness_.size());
        witnesses_ = std::min(witnesses_ + 1, int(witness_.size()));
    }

    // The largest deviation of the samples in the closed triangle (a, b, c) of the polygon's
    // points (counter-clockwise) from its plane, exactly up to `stop`, beyond it some value over
    // it. As the erase measures (scan_hole, measure_hole): the plane's rounding margin at each
    // sample, and at the corners the margin a steep triangle's float corner needs.
    double cost(int a, int b, int c, double stop) {
        const TrianglePlane plane =
            triangle_frame(q_[std::size_t(a)], q_[std::size_t(b)], q_[std::size_t(c)], true,
                           p_[std::size_t(a)].z, p_[std::size_t(b)].z, p_[std::size_t(c)].z)
                .plane;
        const double margin =
            plane.margin_over(p_[std::size_t(a)], p_[std::size_t(b)], p_[std::size_t(c)]);
        double most = 0.0;
        for (const int k : {a, b, c}) {
            const glm::dvec3 &p = p_[std::size_t(k)];
            most = std::max(most,
                            rounding_margin(std::max(std::abs(p.x), std::abs(p.y)), plane.slope()));
        }
        if (most > stop)
            return most;
        // The samples that put a triangle over (most often the node's own) first: the candidate
        // triangles overlap, and most fail on the same few.
        for (int k = 0; k < witnesses_; ++k) {
            const glm::dvec3 w = point(witness_[std::size_t(k)]);
            const glm::dvec2 x(w.x, w.y);
            if (orient(q_[std::size_t(a)], q_[std::size_t(b)], x) > 0.0 &&
                orient(q_[std::size_t(b)], q_[std::size_t(c)], x) > 0.0 &&
                orient(q_[std::size_t(c)], q_[std::size_t(a)], x) > 0.0) {
                const double d = plane.deviation(w.x, w.y, w.z, margin);
                if (d > stop)
                    return d;
            }
        }
        const std::int64_t w = hf_.width;
        const std::int64_t x[3] = {node_[std::size_t(a)] % w, node_[std::size_t(b)] % w,
                                   node_[std::size_t(c)] % w},
                           y[3] = {node_[std::size_t(a)] / w, node_[std::size_t(b)] / w,
                                   node_[std::size_t(c)] / w};
        visit_inside(x, y, [&](std::int64_t col, std::int64_t row) {
            const Mesh::Point p = grid_point(hf_, int(col), int(row));
            most = std::max(most, plane.deviation(p[0], p[1], p[2], margin));
            if (!(most > stop))
                return true;
            add_witness(std::uint32_t(row * w + col));
            return false;
        });
        return most;
    }

    // The min-max triangulation of the polygon `nodes` (v's ring, or it widened by the triangles
    // extra_) within the limit, written over v's star and extra_; false when none holds.
    bool triangulate(const std::vector<std::int32_t> &nodes) {
        const int n = int(nodes.size());
        q_.resize(std::size_t(n));
        p_.resize(std::size_t(n));
        node_.resize(std::size_t(n));
        for (int i = 0; i < n; ++i) {
            node_[std::size_t(i)] = tin_.sample[std::size_t(nodes[std::size_t(i)])];
            p_[std::size_t(i)] = point(node_[std::size_t(i)]);
            q_[std::size_t(i)] = {p_[std::size_t(i)].x, p_[std::size_t(i)].y};
        }
        if (!covered(nodes))
            return false;
        std::array<RingTriangle, k_max_ring> tri;
        const int count = min_max_triangulation(
            q_.data(), n, limit_,
            [this](int a, int b, int c, double stop) { return cost(a, b, c, stop); }, tri.data());
        if (count != n - 2)
            return false;
        old_ = star_;
        old_.insert(old_.end(), extra_.begin(), extra_.end());
        rewrite(nodes, tri.data(), count);
        return true;
    }

    // Whether some triangle a triangulation of the polygon `nodes` (loaded) may hold covers v's
    // sample within the limit (a hair over counts): its closed lattice triangle holds it, no other
    // node of the polygon
    // lies in it, its sides are chords of the polygon (is_ring_chord) and its samples keep within
    // the limit (cost). Else the min-max triangulation finds none; the test costs a few of its
    // triangles, where the search costs all of them.
    bool covered(const std::vector<std::int32_t> &nodes) {
        const int n = int(nodes.size());
        // The triples before coverable's first have v's sample far from their planes, over the
        // same heights (the mesh's are the lattice's on a DEM's nodes; else all are tested).
        bool same = side_nodes_ == &nodes;
        for (int i = 0; i < n; ++i)
            same = same && side_z_[std::size_t(i)] == p_[std::size_t(i)].z;
        Triple from{0, 1, 2};
        if (same)
            from = from_;
        else {
            load_offsets(nodes);
            side_areas(rx_, ry_, std::size_t(n), side_);
            side_nodes_ = &nodes;
            for (int i = 0; i < n; ++i)
                side_z_[std::size_t(i)] = p_[std::size_t(i)].z;
        }
        // known[a][b]: 0 not tested yet, 1 a chord, 2 not (each tested once).
        std::array<std::array<std::uint8_t, k_max_ring>, k_max_ring> known;
        for (int a = 0; a < n; ++a)
            std::fill_n(known[std::size_t(a)].begin(), n, std::uint8_t(0));
        const auto chord = [&](int a, int b) {
            if (b == a + 1 || (a == 0 && b == n - 1))
                return true;
            std::uint8_t &k = known[std::size_t(a)][std::size_t(b)];
            if (k == 0)
                k = is_ring_chord(q_.data(), n, a, b) ? 1 : 2;
            return k == 1;
        };
        return near_triples(
            std::size_t(n), from, [&](std::size_t sa, std::size_t sb, std::size_t sc) {
                const int a = int(sa), b = int(sb), c = int(sc);
                for (int j = 0; j < n; ++j)
                    if (j != a && j != b && j != c &&
                        orient(q_[sa], q_[sb], q_[std::size_t(j)]) >= 0.0 &&
                        orient(q_[sb], q_[sc], q_[std::size_t(j)]) >= 0.0 &&
                        orient(q_[sc], q_[sa], q_[std::size_t(j)]) >= 0.0)
                        return false;
                return chord(a, b) && chord(b, c) && chord(a, c) && cost(a, b, c, limit_) <= limit_;
            });
    }

    // Replaces the triangles old_ (they tile the polygon `nodes`) by `tri` over it.
    void rewrite(const std::vector<std::int32_t> &nodes, const RingTriangle *tri, int count) {
        const std::size_t n = nodes.size();
        // The triangle outside each outline edge nodes[i] -> nodes[i + 1] (-1 on the TIN's
        // outline).
        outside_.assign(n, -1);
        for (std::size_t i = 0; i < n; ++i) {
            const std::int32_t a = nodes[i], b = nodes[(i + 1) % n];
            for (const std::int32_t t : old_)
                for (int k = 0; k < 3; ++k)
                    if (tin_.corner[std::size_t(3 * t + k)] == a &&
                        tin_.corner[std::size_t(3 * t + (k + 1) % 3)] == b)
                        outside_[i] = tin_.across[std::size_t(3 * t + k)];
        }
        for (const std::int32_t t : star_)
            for (int k = 0; k < 3; ++k) {
                const std::int32_t x = tin_.corner[std::size_t(3 * t + k)];
                if (std::find(nodes.begin(), nodes.end(), x) == nodes.end())
                    tin_.fan[std::size_t(x)] = -1; // the erased node
            }
        for (const std::int32_t t : old_)
            tin_.corner[std::size_t(3 * t)] = -1;
        for (int j = 0; j < count; ++j) {
            const std::int32_t t = old_[std::size_t(j)];
            const std::uint8_t c[3] = {tri[j].a, tri[j].b, tri[j].c};
            for (int k = 0; k < 3; ++k) {
                tin_.corner[std::size_t(3 * t + k)] = nodes[c[k]];
                tin_.fan[std::size_t(nodes[c[k]])] = t;
            }
        }
        for (int j = 0; j < count; ++j) {
            const std::int32_t t = old_[std::size_t(j)];
            const std::uint8_t c[3] = {tri[j].a, tri[j].b, tri[j].c};
            for (int k = 0; k < 3; ++k) {
                const std::uint8_t a = c[k], b = c[(k + 1) % 3];
                std::int32_t &link = tin_.across[std::size_t(3 * t + k)];
                if (std::size_t(b) == (std::size_t(a) + 1) % n) {
                    link = outside_[a];
                    if (link >= 0) {
                        const int e = tin_.index_of(link, nodes[b]);
                        tin_.across[std::size_t(3 * link + e)] = t;
                    }
                    continue;
                }
                for (int o = 0; o < count; ++o) {
                    const std::uint8_t d[3] = {tri[o].a, tri[o].b, tri[o].c};
                    for (int e = 0; e < 3; ++e)
                        if (d[e] == b && d[(e + 1) % 3] == a)
                            link = old_[std::size_t(o)];
                }
            }
        }
        outline_ = nodes;
    }

    TinArrays &tin_;
    const Heightfield &hf_;
    const double limit_;
    const int max_ring_;
    std::vector<std::int32_t> ring_, star_, extra_, wide_, old_, outline_, outside_;
    std::vector<int> edge_;
    std::vector<glm::dvec2> q_;
    std::vector<glm::dvec3> p_;
    std::vector<std::uint32_t> node_;
    std::array<std::uint32_t, 8> witness_{};
    // The side areas of the polygon side_nodes_ (null when none), the heights near_triples
    // measures, and coverable's first triple.
    SideAreas side_;
    const std::vector<std::int32_t> *side_nodes_ = nullptr;
    std::array<double, k_max_ring> side_z_{};
    std::array<std::int64_t, k_max_ring> rx_{}, ry_{};
    Triple from_{0, 1, 2};
    int start_[3] = {-1, -1, -1};
    int witnesses_ = 0, next_witness_ = 0;
    std::uint32_t own_ = 0;
    std::size_t own_node_ = 0;
};

} // namespace

Mesh flip_pass(const Mesh &mesh, const Heightfield &hf, double limit, int max_valence,
               FlipPassStats *stats) {
    TinArrays tin = tin_arrays(mesh, hf);
    Pass pass(tin, hf, limit, std::min(max_valence, k_max_ring));
    FlipPassStats out;
    // The outlines of the erases made are tried again. changed: the node's ring changed since the
    // erase (or its last try).
    std::vector<std::uint8_t> changed(tin.sample.size(), 0);
    const std::vector<std::int32_t> none;
    until_none_goes(tin.sample.size(), [&](std::int32_t v) -> const std::vector<std::int32_t> & {
        const int made = pass.erase(v, !changed[std::size_t(v)]);
        changed[std::size_t(v)] = 0;
        if (made == 0)
            return none;
        ++out.erased;
        out.widened += made == 2;
        for (const std::int32_t x : pass.outline())
            changed[std::size_t(x)] = 1;
        return pass.outline();
    });
    Mesh left = nodes_left(tin, mesh);
    if (stats)
        *stats = out;
    return left;
}

} // namespace tinlod::erase
