// The samples a lattice TIN left out, entering it one at a time (lattice_rings.hpp). The TIN is
// copied into flat triangle arrays with integer lattice coordinates (exact predicates), and each
// sample is located by a walk from a corner of its quad-tree node, which is already held.
#include "lattice_rings.hpp"

#include "tinlod/quadtree.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <initializer_list>
#include <stdexcept>
#include <vector>

namespace tinlod {

namespace {

struct Tri {
    std::array<std::uint32_t, 3> v;  // sample ids, counter-clockwise
    std::array<std::int32_t, 3> adj; // the triangle across edge v[k] -> v[k+1], -1 on the outline
};

class Lattice {
  public:
    Lattice(const Mesh &tin, std::uint32_t width, std::uint32_t height,
            std::span<const std::uint32_t> sample_of)
        : w_(width), held_(std::size_t(width) * height, 0),
          vface_(std::size_t(width) * height, -1) {
        const auto sample = [&](Mesh::VertexHandle v) {
            return sample_of.empty() ? std::uint32_t(v.idx()) : sample_of[std::size_t(v.idx())];
        };
        const std::size_t cells = (height - 1) * std::size_t(width - 1);
        tris_.reserve(2 * cells);
        for (auto f : tin.faces()) {
            Tri t;
            auto he = tin.halfedge_handle(f);
            for (int k = 0; k < 3; ++k, he = tin.next_halfedge_handle(he)) {
                t.v[k] = sample(tin.from_vertex_handle(he));
                const auto across = tin.opposite_face_handle(he);
                t.adj[k] = across.is_valid() ? across.idx() : -1;
                vface_[t.v[k]] = f.idx();
            }
            if (f.idx() != std::int32_t(tris_.size()))
                throw std::invalid_argument("absent_sample_rings: the TIN has deleted faces");
            tris_.push_back(t);
        }
        for (auto v : tin.vertices())
            held_[sample(v)] = 1;
    }

    bool held(std::uint32_t c, std::uint32_t r) const { return held_[std::size_t(r) * w_ + c]; }

    // Inserts sample (c, r), located by a walk from the triangle of held sample `from`.
    void insert(std::uint32_t c, std::uint32_t r, std::uint32_t from, const RingVisitor &visit) {
        const std::uint32_t p = r * w_ + c;
        const auto [f, edge] = locate(c, r, vface_[from]);
        std::array<std::uint32_t, 4> ring;
        std::array<std::int32_t, 4> outer; // across ring edge i -> i+1
        std::array<std::int32_t, 4> slot;  // triangles re-used, then appended
        int n = 0, old = 0;
        bool boundary = false;
        const Tri t = tris_[f];
        slot[old++] = f;
        if (edge < 0) {
            for (int k = 0; k < 3; ++k) {
                ring[n] = t.v[k];
                outer[n++] = t.adj[k];
            }
        } else {
            const int k1 = (edge + 1) % 3, k2 = (edge + 2) % 3;
            const std::uint32_t a = t.v[edge], b = t.v[k1], cc = t.v[k2];
            const std::int32_t g = t.adj[edge];
            if (g < 0) { // on the outline: the chain b, c, a
                boundary = true;
                ring = {b, cc, a, 0};
                outer = {t.adj[k1], t.adj[k2], -1, -1};
                n = 3;
            } else {
                const Tri &u = tris_[g];
                const int e = edge_index(u, b, a);
                slot[old++] = g;
                ring = {a, u.v[(e + 2) % 3], b, cc};
                outer = {u.adj[(e + 1) % 3], u.adj[(e + 2) % 3], t.adj[k1], t.adj[k2]};
                n = 4;
            }
        }
        const int fans = boundary ? n - 1 : n;
        for (int k = old; k < fans; ++k) {
            slot[k] = std::int32_t(tris_.size());
            tris_.emplace_back();
        }
        for (int k = 0; k < fans; ++k) {
            Tri &nt = tris_[slot[k]];
            nt.v = {ring[k], ring[(k + 1) % n], p};
            nt.adj[0] = outer[k];
            nt.adj[1] = boundary && k + 1 == fans ? -1 : slot[(k + 1) % n];
            nt.adj[2] = boundary && k == 0 ? -1 : slot[(k + n - 1) % n];
            if (outer[k] >= 0) {
                Tri &o = tris_[outer[k]];
                o.adj[edge_index(o, ring[(k + 1) % n], ring[k])] = slot[k];
            }
            vface_[ring[k]] = slot[k];
        }
        if (boundary)
            vface_[ring[n - 1]] = slot[fans - 1];
        vface_[p] = slot[0];
        held_[p] = 1;
        if (!boundary)
            std::rotate(ring.begin(), std::min_element(ring.begin(), ring.begin() + n),
                        ring.begin() + n);
        visit(p, ring.data(), n, boundary);
    }

  private:
    std::int64_t x(std::uint32_t id) const { return id % w_; }
    std::int64_t y(std::uint32_t id) const { return id / w_; }

    // Twice the signed area of (a, b, (c, r)): > 0 when the point is left of a -> b.
    std::int64_t orient(std::uint32_t a, std::uint32_t b, std::int64_t c, std::int64_t r) const {
        return (x(b) - x(a)) * (r - y(a)) - (y(b) - y(a)) * (c - x(a));
    }

    static int edge_index(const Tri &t, std::uint32_t from, std::uint32_t to) {
        for (int k = 0; k < 3; ++k)
            if (t.v[k] == from && t.v[(k + 1) % 3] == to)
                return k;
        throw std::logic_error("absent_sample_rings: the TIN's triangles do not match");
    }

    // The triangle holding (c, r) and the edge it lies on (-1: inside): a visibility walk that
    // tries the edges from a varying first one, so it cannot circle.
    std::pair<std::int32_t, int> locate(std::int64_t c, std::int64_t r, std::int32_t f) {
        for (std::size_t steps = 0; steps <= tris_.size(); ++steps) {
            const Tri &t = tris_[f];
            rng_ ^= rng_ << 13;
            rng_ ^= rng_ >> 17;
            rng_ ^= rng_ << 5;
            const int first = int(rng_ % 3);
            int on = -1, out = -1;
            for (int q = 0; q < 3 && out < 0; ++q) {
                const int k = (first + q) % 3;
                const std::int64_t o = orient(t.v[k], t.v[(k + 1) % 3], c, r);
                if (o < 0)
                    out = k;
                else if (o == 0)
                    on = k;
            }
            if (out < 0)
                return {f, on};
            f = t.adj[out];
            if (f < 0)
                break;
        }
        throw std::logic_error("absent_sample_rings: a sample lies outside the TIN");
    }

    std::uint32_t w_;
    std::vector<std::uint8_t> held_;
    std::vector<std::int32_t> vface_; // a triangle of each held sample
    std::vector<Tri> tris_;
    std::uint32_t rng_ = 2463534242u;
};

} // namespace

void absent_sample_rings(const Mesh &tin, std::uint32_t width, std::uint32_t height,
                         std::span<const std::uint32_t> sample_of, const RingVisitor &visit) {
    Lattice lattice(tin, width, height, sample_of);
    const QuadLayout layout{int(width), int(height)};
    const auto enter = [&](std::uint32_t c, std::uint32_t r, std::uint32_t from) {
        if (!lattice.held(c, r))
            lattice.insert(c, r, from, visit);
    };
    for (int d = 0; d < layout.levels(); ++d) {
        const std::uint32_t nx = layout.x.count(d), ny = layout.y.count(d);
        for (int phase = 0; phase < 2; ++phase)
            for (std::uint32_t j = 0; j < ny; ++j)
                for (std::uint32_t i = 0; i < nx; ++i) {
                    const std::uint32_t x0 = layout.x.lo(d, i), x1 = layout.x.hi(d, i);
                    const std::uint32_t y0 = layout.y.lo(d, j), y1 = layout.y.hi(d, j);
                    const std::uint32_t mx = (x0 + x1) / 2, my = (y0 + y1) / 2;
                    const std::uint32_t corner = y0 * width + x0;
                    const bool wide = x1 - x0 >= 2, tall = y1 - y0 >= 2;
                    if (phase == 0) {
                        if (wide && tall)
                            enter(mx, my, corner);
                        continue;
                    }
                    if (wide) {
                        enter(mx, y0, corner);
                        enter(mx, y1, corner);
                    }
                    if (tall) {
                        enter(x0, my, corner);
                        enter(x1, my, corner);
                    }
                }
    }
}

} // namespace tinlod

namespace tinlod {

RegularRings::RegularRings(std::uint32_t width, std::uint32_t height)
    : w_(width), h_(height), layout_(int(width), int(height)), level_x_(width, 0),
      level_y_(height, 0) {
    const auto first_levels = [&](const AxisSplit &axis, std::vector<std::uint8_t> &level) {
        std::vector<std::uint8_t> seen(level.size(), 0);
        for (int d = 0; d < layout_.levels(); ++d)
            for (std::uint32_t k = 0; k <= axis.count(d); ++k) {
                const std::uint32_t b = k < axis.count(d) ? axis.lo(d, k) : axis.hi(d, k - 1);
                if (!seen[b]) {
                    seen[b] = 1;
                    level[b] = std::uint8_t(d);
                }
            }
    };
    first_levels(layout_.x, level_x_);
    first_levels(layout_.y, level_y_);
}

bool RegularRings::regular_for_retrievals(std::uint32_t width, std::uint32_t height) {
    return width == height && width >= 3 && ((width - 1) & (width - 2)) == 0;
}

std::size_t RegularRings::bytes() const {
    std::size_t b = level_x_.capacity() + level_y_.capacity();
    for (int d = 0; d < layout_.levels(); ++d) // each axis's bounds, parents and first children
        b += 3 * sizeof(std::uint32_t) * (layout_.x.count(d) + layout_.y.count(d) + 2);
    return b;
}

int RegularRings::ring(std::uint32_t sample, std::uint32_t *ring, bool &boundary) const {
    const std::uint32_t c = sample % w_, r = sample / w_;
    const int a = level_x_[c], b = level_y_[r];
    assert(a > 0 || b > 0);
    const AxisSplit &ax = layout_.x, &ay = layout_.y;
    const auto id = [&](std::uint32_t x, std::uint32_t y) { return y * w_ + x; };
    // The centre of node (d, i, j).
    const auto centre = [&](int d, std::uint32_t i, std::uint32_t j) {
        return id((ax.lo(d, i) + ax.hi(d, i)) / 2, (ay.lo(d, j) + ay.hi(d, j)) / 2);
    };
    // Writes `nodes` to ring; `chain`: an outline's open chain.
    const auto put = [&](std::initializer_list<std::uint32_t> nodes, bool chain) {
        std::copy(nodes.begin(), nodes.end(), ring);
        boundary = chain;
        return int(nodes.size());
    };
    int n = 0;
    if (a == b) { // the centre of a node one level up
        const int d = a - 1;
        const std::uint32_t i = ax.interval_of(d, c), j = ay.interval_of(d, r);
        const std::uint32_t x0 = ax.lo(d, i), x1 = ax.hi(d, i), y0 = ay.lo(d, j), y1 = ay.hi(d, j);
        n = put({id(x0, y0), id(x1, y0), id(x1, y1), id(x0, y1)}, false);
    } else if (a < b) { // the midpoint of a west or east side, x = c
        const int d = b - 1;
        const std::uint32_t j = ay.interval_of(d, r), y0 = ay.lo(d, j), y1 = ay.hi(d, j);
        const std::uint32_t right = ax.bound_index(d, c);
        n = c == 0 ? put({id(c, y0), centre(d, 0, j), id(c, y1)}, true)
            : c == w_ - 1
                ? put({id(c, y1), centre(d, right - 1, j), id(c, y0)}, true)
                : put({id(c, y0), centre(d, right, j), id(c, y1), centre(d, right - 1, j)}, false);
    } else { // the midpoint of a south or north side, y = r
        const int d = a - 1;
        const std::uint32_t i = ax.interval_of(d, c), x0 = ax.lo(d, i), x1 = ax.hi(d, i);
        const std::uint32_t above = ay.bound_index(d, r);
        n = r == 0 ? put({id(x1, r), centre(d, i, 0), id(x0, r)}, true)
            : r == h_ - 1
                ? put({id(x0, r), centre(d, i, above - 1), id(x1, r)}, true)
                : put({id(x1, r), centre(d, i, above), id(x0, r), centre(d, i, above - 1)}, false);
    }
    if (!boundary)
        std::rotate(ring, std::min_element(ring, ring + n), ring + n);
    return n;
}

} // namespace tinlod
