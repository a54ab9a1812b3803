// The quad-tree of a Heightfield and its view-dependent retrieval (see quadtree.hpp): conservative
// node bounds built bottom-up over every sample (Lindstrom et al. 1996), a top-down traversal that
// splits a node when its bound seen from the nearest point of its box exceeds the tolerance (the
// paper's method 1), kept restricted as in Röttger et al. 1998 / Pajarola 1998 so the per-node
// triangle fans meet without cracks.
#include "tinlod/quadtree.hpp"

#include "float_rounding.hpp"
#include "node_bound.hpp"
#include "tinlod/error.hpp"
#include "tinlod/screen_weight.hpp"
#include "tinlod/util.hpp"
#include "triangle_plane.hpp"
#include "working_set.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <thread>
#include <utility>

namespace tinlod {

// ---------------------------------------------------------------------------------------------
// Layout

int AxisSplit::levels_for(int samples) {
    assert(samples >= 2);
    int levels = 1;
    for (int len = samples - 1; len > 1; len = (len + 1) / 2)
        ++levels;
    return levels;
}

AxisSplit::AxisSplit(int samples, int levels) {
    assert(samples >= 2 && levels >= levels_for(samples));
    starts_.assign(levels, {});
    parent_.assign(levels, {});
    first_child_.assign(levels, {});
    starts_[0] = {0, static_cast<std::uint32_t>(samples - 1)};
    parent_[0] = {0};
    for (int d = 1; d < levels; ++d) {
        const auto &prev = starts_[d - 1];
        auto &cur = starts_[d];
        auto &fc = first_child_[d - 1];
        fc.resize(prev.size() - 1);
        for (std::uint32_t k = 0; k + 1 < prev.size(); ++k) {
            fc[k] = static_cast<std::uint32_t>(cur.size());
            const std::uint32_t a = prev[k], b = prev[k + 1];
            cur.push_back(a);
            parent_[d].push_back(k);
            if (b - a >= 2) {
                cur.push_back((a + b) / 2);
                parent_[d].push_back(k);
            }
        }
        cur.push_back(prev.back());
    }
}

std::uint32_t AxisSplit::bound_index(int d, std::uint32_t s) const {
    const auto &st = starts_[d];
    const auto it = std::lower_bound(st.begin(), st.end(), s);
    assert(it != st.end() && *it == s);
    return static_cast<std::uint32_t>(it - st.begin());
}

std::uint32_t AxisSplit::interval_of(int d, std::uint32_t s) const {
    const auto &st = starts_[d];
    assert(s < st.back());
    return static_cast<std::uint32_t>(std::upper_bound(st.begin(), st.end(), s) - st.begin() - 1);
}

QuadLayout::QuadLayout(int w, int h) : width(w), height(h) {
    const int levels = std::max(AxisSplit::levels_for(w), AxisSplit::levels_for(h));
    x = AxisSplit(w, levels);
    y = AxisSplit(h, levels);
}

// ---------------------------------------------------------------------------------------------
// Bounds

namespace {

// The gradient form of a fan triangle's plane over grid positions (c, r): a node's bound is the
// most numerous scan of the build.
using Plane = TrianglePlane::Rows;

// A node at least two cells wide and tall: a fan around its centre over the four corners, each
// side optionally split at its midpoint. The four wedges are independent, so the worst case over
// the 16 variants is, per sample, the worse of its wedge with and without the side midpoint. Each
// row crosses the wedges in at most three spans (cut by the diagonals), and inside a span the half
// of the split wedge is fixed by the row or by the centre column.
OwnBound fan_bound(const GridRows &rows, std::uint32_t x0, std::uint32_t x1, std::uint32_t y0,
                   std::uint32_t y1, std::uint32_t ra, std::uint32_t rb, bool box) {
    auto at = [&](std::uint32_t c, std::uint32_t r) {
        return glm::dvec3(double(c), double(r), double(rows.at(c, r)));
    };
    const auto plane = TrianglePlane::rows;
    const std::uint32_t mx = (x0 + x1) / 2, my = (y0 + y1) / 2;
    const glm::dvec3 ctr = at(mx, my);
    const glm::dvec3 bl = at(x0, y0), br = at(x1, y0), tr = at(x1, y1), tl = at(x0, y1);
    const glm::dvec3 mb = at(mx, y0), mr = at(x1, my), mt = at(mx, y1), ml = at(x0, my);
    // Wedges bottom, right, top, left: the whole triangle and its two halves.
    const Plane full[4] = {plane(ctr, bl, br), plane(ctr, br, tr), plane(ctr, tr, tl),
                           plane(ctr, tl, bl)};
    const Plane bottom[2] = {plane(ctr, bl, mb), plane(ctr, mb, br)}; // c <= mx, c >= mx
    const Plane top[2] = {plane(ctr, mt, tl), plane(ctr, tr, mt)};    // c <= mx, c >= mx
    const Plane right[2] = {plane(ctr, br, mr), plane(ctr, mr, tr)};  // r <= my, r >= my
    const Plane left[2] = {plane(ctr, ml, bl), plane(ctr, tl, ml)};   // r <= my, r >= my
    OwnBound out;
    double e = 0.0;
    auto span = [&](const float *row, double r, std::uint32_t c0, std::uint32_t c1, const Plane &a,
                    const Plane &b) {
        const double za = a.start(r), zb = b.start(r);
        for (std::uint32_t c = c0; c <= c1; ++c) {
            const double zs = row[c];
            e = std::max(e, std::max(a.deviation(za, c, zs), b.deviation(zb, c, zs)));
        }
    };
    for (std::uint32_t r = std::max(y0, ra); r <= std::min(y1, rb); ++r) {
        const float *row = rows.row(r);
        if (box)
            for (std::uint32_t c = x0; c <= x1; ++c)
                out.box(row[c]);
        const double rr = r;
        const bool below = r <= my;
        const double t = below ? double(my - r) / (my - y0) : double(r - my) / (y1 - my);
        // Columns up to `lo` lie in the left wedge, from `hi` in the right one.
        const auto lo = static_cast<std::int64_t>(std::floor(mx - (mx - x0) * t));
        const auto hi = static_cast<std::int64_t>(std::ceil(mx + (x1 - mx) * t));
        const Plane &lh = left[below ? 0 : 1];
        const Plane &rh = right[below ? 0 : 1];
        span(row, rr, x0, std::uint32_t(lo), full[3], lh);
        span(row, rr, std::uint32_t(hi), x1, full[1], rh);
        const Plane &mid = full[below ? 0 : 2];
        const Plane *halves = below ? bottom : top;
        if (std::int64_t(mx) > lo)
            span(row, rr, std::uint32_t(lo), mx, mid, halves[0]);
        if (std::int64_t(mx) < hi)
            span(row, rr, mx, std::uint32_t(hi), mid, halves[1]);
    }
    out.error = e;
    return out;
}

// A node of 2x2 cells (the most numerous): every sample is a vertex of the fan with all side
// midpoints, so the error is that of a side midpoint left out.
OwnBound small_bound(const GridRows &rows, std::uint32_t x0, std::uint32_t y0) {
    OwnBound out;
    float s[3][3];
    for (std::uint32_t r = 0; r < 3; ++r)
        for (std::uint32_t c = 0; c < 3; ++c)
            out.box(s[r][c] = rows.row(y0 + r)[x0 + c]);
    auto gap = [](float m, float a, float b) {
        return std::abs(double(m) - 0.5 * (double(a) + b));
    };
    out.error = std::max({gap(s[0][1], s[0][0], s[0][2]), gap(s[2][1], s[2][0], s[2][2]),
                          gap(s[1][0], s[0][0], s[2][0]), gap(s[1][2], s[0][2], s[2][2])});
    return out;
}

// One side of a one-cell-wide node: samples z(0..n) along it, optionally split at n/2, over its
// samples s0..s1. In such a node every sample lies on a side, so the sides alone give the bound.
template <class Z>
double side_bound(Z z, std::uint32_t n, std::uint32_t s0 = 0,
                  std::uint32_t s1 = std::numeric_limits<std::uint32_t>::max()) {
    const std::uint32_t m = n / 2;
    const double z0 = z(0), zm = z(m), zn = z(n);
    double e = 0.0;
    for (std::uint32_t s = std::max(s0, 1u); s < n && s <= s1; ++s) {
        const double zs = z(s);
        const double whole = z0 + (zn - z0) * s / n;
        const double half = s <= m ? z0 + (zm - z0) * s / m : zm + (zn - zm) * (s - m) / (n - m);
        e = std::max({e, std::abs(zs - whole), std::abs(zs - half)});
    }
    return e;
}

OwnBound strip_bound(const GridRows &rows, std::uint32_t x0, std::uint32_t x1, std::uint32_t y0,
                     std::uint32_t y1, std::uint32_t ra, std::uint32_t rb, bool box) {
    OwnBound out;
    const std::uint32_t r0 = std::max(y0, ra), r1 = std::min(y1, rb);
    if (box)
        for (std::uint32_t r = r0; r <= r1; ++r)
            for (std::uint32_t c = x0; c <= x1; ++c)
                out.box(rows.row(r)[c]);
    if (x1 - x0 == 1) {
        for (std::uint32_t c : {x0, x1})
            out.error = std::max(
                out.error, side_bound([&](std::uint32_t s) { return double(rows.at(c, y0 + s)); },
                                      y1 - y0, r0 - y0, r1 - y0));
    } else if (y1 - y0 == 1) {
        for (std::uint32_t r : {y0, y1})
            if (r >= r0 && r <= r1)
                out.error = std::max(
                    out.error,
                    side_bound([&](std::uint32_t s) { return double(rows.row(r)[x0 + s]); },
                               x1 - x0));
    }
    return out;
}

} // namespace

OwnBound own_bound(const GridRows &rows, std::uint32_t x0, std::uint32_t x1, std::uint32_t y0,
                   std::uint32_t y1, std::uint32_t ra, std::uint32_t rb, bool box) {
    if (x1 - x0 == 2 && y1 - y0 == 2) {
        assert(ra <= y0 && rb >= y1);
        return small_bound(rows, x0, y0);
    }
    return x1 - x0 >= 2 && y1 - y0 >= 2 ? fan_bound(rows, x0, x1, y0, y1, ra, rb, box)
                                        : strip_bound(rows, x0, x1, y0, y1, ra, rb, box);
}

void check_quad_grid(int width, int height) {
    if (width < 2 || height < 2)
        throw Error("quad-tree", "the grid must be at least 2x2 samples, got " +
                                     std::to_string(width) + "x" + std::to_string(height));
    if (std::int64_t{width} * height > k_max_raster_samples)
        throw Error("quad-tree", "the grid has more than 2^31 samples");
}

static void check_grid(const Heightfield &hf) {
    check_quad_grid(hf.width, hf.height);
    assert(hf.z.size() == static_cast<std::size_t>(hf.size()));
}

QuadTree::QuadTree(const Heightfield &hf, Progress *progress) {
    check_grid(hf);
    // On huge pages, asked for before the first touch (as the bounds below): one fault per 2 MB
    // instead of 512.
    z_.reserve(hf.z.size());
    advise_huge_pages(z_.data(), hf.z.size() * sizeof(float));
    z_.assign(hf.z.begin(), hf.z.end());
    build(hf, progress);
}

QuadTree::QuadTree(Heightfield &&hf, Progress *progress) {
    check_grid(hf);
    z_ = std::move(hf.z);
    build(hf, progress);
}

void QuadTree::build(const Heightfield &hf, Progress *progress) {
    layout_ = QuadLayout(hf.width, hf.height);
    frame_ = {hf.width, hf.height, hf.dx, hf.dy, hf.origin_x, hf.origin_y, hf.crs};
    const int levels = layout_.levels();
    bounds_.resize(std::max(levels - 1, 0));
    GridRows grid;
    grid.band = z_.data();
    grid.width = hf.width;
    grid.r1 = static_cast<std::uint32_t>(hf.height - 1);
    std::int64_t done = 0;
    for (int d = levels - 2; d >= 0; --d) {
        const std::uint32_t nx = layout_.x.count(d), ny = layout_.y.count(d);
        auto &level = bounds_[d];
        level.reserve(std::size_t{nx} * ny);
        advise_huge_pages(level.data(), std::size_t{nx} * ny * sizeof(NodeBound));
        level.resize(std::size_t{nx} * ny);
        // A node with children gets its z box from theirs, which cover its samples: a pass over
        // every sample per level took a third of the build.
        const bool leaf = d + 1 >= levels - 1;
        auto rows = [&](std::uint32_t j0, std::uint32_t j1) {
            for (std::uint32_t j = j0; j < j1; ++j)
                for (std::uint32_t i = 0; i < nx; ++i) {
                    const std::uint32_t x0 = layout_.x.lo(d, i), x1 = layout_.x.hi(d, i);
                    const std::uint32_t y0 = layout_.y.lo(d, j), y1 = layout_.y.hi(d, j);
                    level[std::size_t{j} * nx + i] = node_bound(
                        layout_, d, i, j, own_bound(grid, x0, x1, y0, y1, y0, y1, leaf),
                        [&](std::uint32_t ci, std::uint32_t cj) { return bound(d + 1, ci, cj); });
                }
        };
        // Rows of nodes are independent (the level below is complete): split them over threads.
        const std::uint32_t workers = std::min<std::uint32_t>(max_threads(), ny);
        std::vector<std::thread> pool;
        for (std::uint32_t t = 1; t < workers; ++t)
            pool.emplace_back(rows, ny * t / workers, ny * (t + 1) / workers);
        rows(0, ny / workers);
        for (auto &th : pool)
            th.join();
        done += hf.size();
        if (progress)
            progress->update(done);
    }
}

std::int64_t QuadTree::node_count() const {
    std::int64_t n = 0;
    for (const auto &level : bounds_)
        n += static_cast<std::int64_t>(level.size());
    return n;
}

// ---------------------------------------------------------------------------------------------
// Retrieval

namespace {

class MemorySource final : public NodeSource {
  public:
    explicit MemorySource(const QuadTree &tree) : tree_(tree) {}
    const QuadLayout &layout() const override { return tree_.layout(); }
    const GridFrame &frame() const override { return tree_.frame(); }
    NodeBound bound(int d, std::uint32_t i, std::uint32_t j) override {
        return tree_.bound(d, i, j);
    }
    float vertex_z(int, std::uint32_t, std::uint32_t, std::uint32_t c, std::uint32_t r) override {
        return tree_.elevation(c, r);
    }

  private:
    const QuadTree &tree_;
};

// Zero-initialised arrays from calloc: untouched pages of a large status array cost no memory.
struct FreeDeleter {
    void operator()(void *p) const { std::free(p); }
};
template <class T> std::unique_ptr<T[], FreeDeleter> zeroed(std::size_t n) {
    void *p = std::calloc(std::max<std::size_t>(n, 1), sizeof(T));
    if (!p)
        throw std::bad_alloc();
    return std::unique_ptr<T[], FreeDeleter>(static_cast<T *>(p));
}

constexpr std::uint8_t k_unread = 0, k_leaf = 1, k_split = 2;

std::uint64_t pack(int d, std::uint32_t i, std::uint32_t j) {
    return (std::uint64_t(d) << 58) | (std::uint64_t(i) << 29) | j;
}

} // namespace

struct QuadTreeLod::Impl {
    std::unique_ptr<NodeSource> source;
    const QuadLayout *lay = nullptr;
    int last = 0; // the level of one-cell nodes only; it has no status array
    std::vector<std::unique_ptr<std::uint8_t[], FreeDeleter>> status;
    std::unique_ptr<std::uint64_t[], FreeDeleter> emitted; // one bit per sample
    std::vector<std::uint64_t> touched;                    // every node given a status
    std::vector<std::vector<std::uint64_t>> pending;       // per level: created nodes to evaluate
    std::vector<std::size_t> cursor;                       // per level: first not yet evaluated
    Retrieval out;

    // The view of the retrieval in progress.
    glm::dvec3 eye{0.0};
    double k = 1.0, tol = 1.0, dx = 1.0, dy = 1.0;
    bool cull = false;
    bool weigh = false; // RetrieveOptions::peripheral given
    Weigher weigher;
    glm::dvec3 planes[5]; // the frustum: p is inside when dot(plane, p - eye) <= 0 for all

    explicit Impl(std::unique_ptr<NodeSource> src) : source(std::move(src)) {
        lay = &source->layout();
        last = lay->levels() - 1;
        for (int d = 0; d < last; ++d)
            status.push_back(zeroed<std::uint8_t>(lay->level_nodes(d)));
        pending.resize(last);
        cursor.assign(last, 0);
        emitted = zeroed<std::uint64_t>((std::size_t(lay->width) * lay->height + 63) / 64);
        dx = source->frame().dx;
        dy = source->frame().dy;
    }

    std::uint8_t &st(int d, std::uint32_t i, std::uint32_t j) {
        return status[d][std::size_t{j} * lay->x.count(d) + i];
    }

    void set_view(const View &view, const RetrieveOptions &options) {
        eye = view.eye;
        k = view.k();
        tol = options.tolerance;
        cull = options.cull;
        weigh = options.peripheral != nullptr;
        if (weigh)
            weigher = Weigher(view, *options.peripheral);
        const auto [f, r, u] = view.frame();
        const double hw = view.viewport_w / 2.0, hh = view.viewport_h / 2.0;
        planes[0] = k * r - hw * f;
        planes[1] = -k * r - hw * f;
        planes[2] = k * u - hh * f;
        planes[3] = -k * u - hh * f;
        planes[4] = -f;
    }

    bool outside_frustum(const glm::dvec3 &lo, const glm::dvec3 &hi) const {
        for (const glm::dvec3 &n : planes) {
            // The box corner deepest inside this plane; slack of a micrometre for rounding.
            const glm::dvec3 p(n.x > 0 ? lo.x : hi.x, n.y > 0 ? lo.y : hi.y, n.z > 0 ? lo.z : hi.z);
            if (glm::dot(n, p - eye) > 1e-6 * glm::length(n))
                return true;
        }
        return false;
    }

    bool wants_split(int d, std::uint32_t i, std::uint32_t j) {
        if (lay->is_cell(d, i, j))
            return false;
        if (tol <= 0.0)
            return true;
        const NodeBound b = source->bound(d, i, j);
        const glm::dvec3 lo(lay->x.lo(d, i) * dx, lay->y.lo(d, j) * dy, b.zmin);
        const glm::dvec3 hi(lay->x.hi(d, i) * dx, lay->y.hi(d, j) * dy, b.zmax);
        if (cull && outside_frustum(lo, hi))
            return false;
        if (weigh) {
            const double px = b.error * weigher.bound(lo, hi);
            if (!(px <= tol))
                return true;
            out.bound_px = std::max(out.bound_px, px);
            return false;
        }
        const glm::dvec3 gap = glm::max(glm::max(lo - eye, eye - hi), glm::dvec3(0.0));
        const double dist = glm::length(gap);
        const double px = b.error * k;
        if (px > tol * dist)
            return true;
        if (dist > 0.0)
            out.bound_px = std::max(out.bound_px, px / dist);
        return false;
    }

    void create(int d, std::uint32_t i, std::uint32_t j) {
        touched.push_back(pack(d, i, j));
        if (d < last) {
            st(d, i, j) = k_leaf;
            pending[d].push_back(touched.back());
        }
    }

    // Splits an existing node of level d at the request of a finer neighbour: its own neighbours
    // first (recursion climbs one level per call, so its depth is bounded by the tree's).
    void force(int d, std::uint32_t i, std::uint32_t j) {
        if (st(d, i, j) == k_unread)
            force(d - 1, lay->x.parent(d, i), lay->y.parent(d, j));
        if (st(d, i, j) != k_split) {
            ++out.forced;
            split(d, i, j);
        }
    }

    // Marks the node split and creates its children (evaluated later, level by level). The
    // restriction: the neighbours across every side that splits must exist, so no leaf meets a
    // node more than one level finer and the fans meet without T-junctions.
    void split(int d, std::uint32_t i, std::uint32_t j) {
        st(d, i, j) = k_split;
        const std::uint32_t lx = lay->x.length(d, i), ly = lay->y.length(d, j);
        const std::uint32_t cx = lay->x.first_child(d, i), cy = lay->y.first_child(d, j);
        const std::uint32_t ncx = lx >= 2 ? 2 : 1, ncy = ly >= 2 ? 2 : 1;
        for (std::uint32_t b = 0; b < ncy; ++b)
            for (std::uint32_t a = 0; a < ncx; ++a)
                create(d + 1, cx + a, cy + b);
        const std::uint32_t nx = lay->x.count(d), ny = lay->y.count(d);
        auto need = [&](std::uint32_t ni, std::uint32_t nj) {
            if (st(d, ni, nj) == k_unread)
                force(d - 1, lay->x.parent(d, ni), lay->y.parent(d, nj));
        };
        if (ly >= 2) {
            if (i > 0)
                need(i - 1, j);
            if (i + 1 < nx)
                need(i + 1, j);
        }
        if (lx >= 2) {
            if (j > 0)
                need(i, j - 1);
            if (j + 1 < ny)
                need(i, j + 1);
        }
    }

    // Evaluates the created nodes level by level; a forced split may create nodes on a level
    // already done, so the sweep goes back to the lowest level with work left.
    void traverse() {
        int d = 0;
        while (d < last) {
            auto &queue = pending[d];
            while (cursor[d] < queue.size()) {
                const std::uint64_t key = queue[cursor[d]++];
                const std::uint32_t i = (key >> 29) & 0x1fffffff, j = key & 0x1fffffff;
                if (st(d, i, j) != k_split && wants_split(d, i, j))
                    split(d, i, j);
            }
            int next = d + 1;
            for (int e = 0; e <= d; ++e)
                if (cursor[e] < pending[e].size()) {
                    next = e;
                    break;
                }
            d = next;
        }
    }

    void reset() {
        for (std::uint64_t key : touched) {
            const int d = static_cast<int>(key >> 58);
            if (d < last)
                st(d, (key >> 29) & 0x1fffffff, key & 0x1fffffff) = k_unread;
        }
        touched.clear();
        for (int d = 0; d < last; ++d) {
            pending[d].clear();
            cursor[d] = 0;
        }
        for (std::uint32_t id : out.nodes)
            emitted[id >> 6] &= ~(std::uint64_t{1} << (id & 63));
        out.nodes.clear();
        out.z.clear();
        out.triangles.clear();
        out.tree_nodes = out.leaves = out.forced = 0;
        out.bound_px = 0.0;
    }

    std::uint32_t vertex(int d, std::uint32_t i, std::uint32_t j, std::uint32_t c,
                         std::uint32_t r) {
        const std::uint32_t id = r * static_cast<std::uint32_t>(lay->width) + c;
        std::uint64_t &word = emitted[id >> 6];
        const std::uint64_t bit = std::uint64_t{1} << (id & 63);
        if (!(word & bit)) {
            word |= bit;
            out.nodes.push_back(id);
            out.z.push_back(source->vertex_z(d, i, j, c, r));
        }
        return id;
    }

    void tri(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        out.triangles.insert(out.triangles.end(), {a, b, c});
    }

    bool split_at(int d, std::uint32_t i, std::uint32_t j) {
        return d < last && st(d, i, j) == k_split;
    }

    // The leaf's triangles, counter-clockwise from above: a fan around the centre over the
    // corners and the midpoints of the sides whose neighbour is split (a one-cell-wide leaf has no
    // centre and gets its few triangles case by case).
    void emit_leaf(int d, std::uint32_t i, std::uint32_t j) {
        const std::uint32_t x0 = lay->x.lo(d, i), x1 = lay->x.hi(d, i);
        const std::uint32_t y0 = lay->y.lo(d, j), y1 = lay->y.hi(d, j);
        auto v = [&](std::uint32_t c, std::uint32_t r) { return vertex(d, i, j, c, r); };
        const std::uint32_t bl = v(x0, y0), br = v(x1, y0), tr = v(x1, y1), tl = v(x0, y1);
        const std::uint32_t lx = x1 - x0, ly = y1 - y0;
        const std::uint32_t mx = (x0 + x1) / 2, my = (y0 + y1) / 2;
        const bool bottom = lx >= 2 && j > 0 && split_at(d, i, j - 1);
        const bool top = lx >= 2 && j + 1 < lay->y.count(d) && split_at(d, i, j + 1);
        const bool left = ly >= 2 && i > 0 && split_at(d, i - 1, j);
        const bool right = ly >= 2 && i + 1 < lay->x.count(d) && split_at(d, i + 1, j);
        if (lx >= 2 && ly >= 2) {
            std::uint32_t ring[8];
            int n = 0;
            ring[n++] = bl;
            if (bottom)
                ring[n++] = v(mx, y0);
            ring[n++] = br;
            if (right)
                ring[n++] = v(x1, my);
            ring[n++] = tr;
            if (top)
                ring[n++] = v(mx, y1);
            ring[n++] = tl;
            if (left)
                ring[n++] = v(x0, my);
            const std::uint32_t ctr = v(mx, my);
            for (int s = 0; s < n; ++s)
                tri(ctr, ring[s], ring[(s + 1) % n]);
        } else if (lx == 1 && ly >= 2 && (left || right)) {
            if (left && right) {
                const std::uint32_t l = v(x0, my), r = v(x1, my);
                tri(bl, br, r);
                tri(bl, r, l);
                tri(l, r, tr);
                tri(l, tr, tl);
            } else if (right) {
                const std::uint32_t r = v(x1, my);
                tri(bl, br, r);
                tri(bl, r, tl);
                tri(r, tr, tl);
            } else {
                const std::uint32_t l = v(x0, my);
                tri(bl, br, l);
                tri(br, tr, l);
                tri(tr, tl, l);
            }
        } else if (ly == 1 && lx >= 2 && (bottom || top)) {
            if (bottom && top) {
                const std::uint32_t b = v(mx, y0), t = v(mx, y1);
                tri(bl, b, t);
                tri(bl, t, tl);
                tri(b, br, tr);
                tri(b, tr, t);
            } else if (bottom) {
                const std::uint32_t b = v(mx, y0);
                tri(bl, b, tl);
                tri(b, br, tr);
                tri(b, tr, tl);
            } else {
                const std::uint32_t t = v(mx, y1);
                tri(bl, br, t);
                tri(br, tr, t);
                tri(bl, t, tl);
            }
        } else {
            tri(bl, br, tr);
            tri(bl, tr, tl);
        }
    }

    const Retrieval &run(const View &view, const RetrieveOptions &options) {
        if (!(options.tolerance >= 0.0))
            throw Error("RetrieveOptions::tolerance",
                        "must be 0 or more (pixels), not " + std::to_string(options.tolerance));
        reset();
        set_view(view, options);
        source->begin_retrieval();
        try {
            create(0, 0, 0);
            traverse();
            for (std::uint64_t key : touched) {
                const int d = static_cast<int>(key >> 58);
                const std::uint32_t i = (key >> 29) & 0x1fffffff, j = key & 0x1fffffff;
                if (split_at(d, i, j))
                    continue;
                ++out.leaves;
                emit_leaf(d, i, j);
            }
        } catch (...) {
            source->end_retrieval();
            throw;
        }
        source->end_retrieval();
        out.tree_nodes = static_cast<std::int64_t>(touched.size());
        return out;
    }
};

QuadTreeLod::QuadTreeLod(const QuadTree &tree)
    : impl_(std::make_unique<Impl>(std::make_unique<MemorySource>(tree))) {}

QuadTreeLod::QuadTreeLod(std::unique_ptr<NodeSource> source)
    : impl_(std::make_unique<Impl>(std::move(source))) {}

namespace {

// A source the traversal reads but does not own.
class BorrowedSource final : public NodeSource {
  public:
    explicit BorrowedSource(NodeSource &source) : s_(source) {}
    const QuadLayout &layout() const override { return s_.layout(); }
    const GridFrame &frame() const override { return s_.frame(); }
    NodeBound bound(int d, std::uint32_t i, std::uint32_t j) override { return s_.bound(d, i, j); }
    float vertex_z(int d, std::uint32_t i, std::uint32_t j, std::uint32_t c,
                   std::uint32_t r) override {
        return s_.vertex_z(d, i, j, c, r);
    }
    void begin_retrieval() override { s_.begin_retrieval(); }
    void end_retrieval() override { s_.end_retrieval(); }

  private:
    NodeSource &s_;
};

} // namespace

QuadTreeLod::QuadTreeLod(NodeSource &source)
    : impl_(std::make_unique<Impl>(std::make_unique<BorrowedSource>(source))) {}

QuadTreeLod::~QuadTreeLod() = default;

const Retrieval &QuadTreeLod::retrieve(const View &view, const RetrieveOptions &options) {
    return impl_->run(view, options);
}

const QuadLayout &QuadTreeLod::layout() const { return *impl_->lay; }
const GridFrame &QuadTreeLod::frame() const { return impl_->source->frame(); }

NodeStatus QuadTreeLod::status(int d, std::uint32_t i, std::uint32_t j) const {
    assert(d >= 0 && d <= impl_->last);
    if (d == impl_->last) {
        if (d == 0)
            return NodeStatus::leaf;
        const std::uint8_t p =
            impl_->st(d - 1, impl_->lay->x.parent(d, i), impl_->lay->y.parent(d, j));
        return p == k_split ? NodeStatus::leaf : NodeStatus::unread;
    }
    switch (impl_->st(d, i, j)) {
    case k_leaf:
        return NodeStatus::leaf;
    case k_split:
        return NodeStatus::subdivide;
    default:
        return NodeStatus::unread;
    }
}

Retrieval retrieve(const QuadTree &tree, const View &view, const RetrieveOptions &options) {
    QuadTreeLod lod(tree);
    return lod.retrieve(view, options);
}

// ---------------------------------------------------------------------------------------------
// The heights a TIN's bound rests on

int level_for_cells(const QuadLayout &layout, int cells) {
    const auto widest = [](const AxisSplit &axis, int d) {
        std::uint32_t most = 0;
        for (std::uint32_t k = 0; k < axis.count(d); ++k)
            most = std::max(most, axis.length(d, k));
        return most;
    };
    int d = 0;
    while (d < layout.levels() - 2 &&
           std::max(widest(layout.x, d), widest(layout.y, d)) > std::uint32_t(std::max(cells, 1)))
        ++d;
    return d;
}

namespace {

// Within this many cells of a face counts as on it: the face's corners are the grid's float
// coordinates over the spacing, a few 1e-5 cells off the lattice on a 4097² grid.
constexpr double k_on_face = 1e-3;

// One live face in lattice units (u = column, v = row) with its plane in the world frame.
struct WorkingFace {
    std::array<glm::dvec2, 3> q; // corners, lattice units
    std::array<glm::dvec3, 3> p; // corners, world
    glm::dvec2 lo, hi;           // its box, lattice units
    glm::dvec3 normal;           // cross(p1 - p0, p2 - p0): normal.z > 0 for a CCW face
    TrianglePlane plane;         // world frame
    // Whether the closed face meets the closed rectangle [x0, x1] x [y0, y1] (separating axes: the
    // box's, then each edge's normal).
    bool meets(double x0, double y0, double x1, double y1) const {
        if (hi.x < x0 || lo.x > x1 || hi.y < y0 || lo.y > y1)
            return false;
        for (int i = 0; i < 3; ++i) {
            const glm::dvec2 a = q[i], b = q[(i + 1) % 3];
            const glm::dvec2 inward(a.y - b.y, b.x - a.x); // left of a -> b: inside a CCW face
            double most = -INFINITY;
            for (const double x : {x0, x1})
                for (const double y : {y0, y1})
                    most = std::max(most, glm::dot(inward, glm::dvec2(x, y) - a));
            if (most < -k_on_face * glm::length(inward))
                return false;
        }
        return true;
    }
    // Whether lattice sample (c, r), not a corner, lies inside or on the face.
    bool holds(std::uint32_t c, std::uint32_t r) const {
        const glm::dvec2 s(c, r);
        for (int i = 0; i < 3; ++i) {
            if (glm::length(s - q[i]) < k_on_face)
                return false;
            const glm::dvec2 a = q[i], b = q[(i + 1) % 3];
            const double left = (b.x - a.x) * (s.y - a.y) - (b.y - a.y) * (s.x - a.x);
            if (left < -k_on_face * glm::length(b - a))
                return false;
        }
        return true;
    }
};

} // namespace

WorkingSet height_working_set(const QuadTree &tree, const Mesh &tin, const View &view,
                              const SignificanceOptions &significance, double tol_px, int level) {
    const QuadLayout &lay = tree.layout();
    const GridFrame &frame = tree.frame();
    if (lay.levels() < 2 || level < 0 || level > lay.levels() - 2)
        throw std::invalid_argument("height_working_set: level " + std::to_string(level) +
                                    " has no node bounds");
    const Weigher weigher(view, significance);
    WorkingSet out;
    out.level = level;
    out.needed.assign(std::size_t(lay.level_nodes(level)), 0);
    struct Node {
        int d;
        std::uint32_t i, j;
    };
    std::vector<Node> stack;
    for (const auto f : tin.faces()) {
        if (tin.status(f).deleted())
            continue;
        WorkingFace face;
        int k = 0;
        for (const auto v : tin.fv_range(f)) {
            const Mesh::Point &point = tin.point(v);
            face.p[k] = glm::dvec3(point[0], point[1], point[2]);
            face.q[k] = glm::dvec2(face.p[k].x / frame.dx, face.p[k].y / frame.dy);
            ++k;
        }
        face.normal = glm::cross(face.p[1] - face.p[0], face.p[2] - face.p[0]);
        if (!(face.normal.z > 0.0))
            continue; // degenerate in xy: it covers no sample
        face.plane = TrianglePlane(face.p[0], face.p[1], face.p[2]);
        face.lo = glm::min(face.q[0], glm::min(face.q[1], face.q[2]));
        face.hi = glm::max(face.q[0], glm::max(face.q[1], face.q[2]));
        stack.assign(1, {0, 0, 0});
        while (!stack.empty()) {
            const Node n = stack.back();
            stack.pop_back();
            const std::uint32_t x0 = lay.x.lo(n.d, n.i), x1 = lay.x.hi(n.d, n.i);
            const std::uint32_t y0 = lay.y.lo(n.d, n.j), y1 = lay.y.hi(n.d, n.j);
            if (!face.meets(x0, y0, x1, y1))
                continue;
            const NodeBound &b = tree.bound(n.d, n.i, n.j);
            if (x1 - x0 >= 2 && y1 - y0 >= 2) {
                const std::uint32_t mx = (x0 + x1) / 2, my = (y0 + y1) / 2;
                double dev = 0.0;
                for (const auto &[c, r] : {std::pair{x0, y0}, std::pair{x1, y0}, std::pair{x0, y1},
                                           std::pair{x1, y1}, std::pair{mx, my}}) {
                    const double x = double(float(c * frame.dx)), y = double(float(r * frame.dy));
                    dev = std::max(
                        dev, std::abs(double(tree.elevation(c, r)) - face.plane.height(x, y)));
                }
                const glm::dvec3 lo(std::max(double(x0), face.lo.x) * frame.dx,
                                    std::max(double(y0), face.lo.y) * frame.dy, b.zmin);
                const glm::dvec3 hi(std::min(double(x1), face.hi.x) * frame.dx,
                                    std::min(double(y1), face.hi.y) * frame.dy, b.zmax);
                // A hair over the sum, for its rounding and the float grid coordinates.
                if ((double(b.error) + dev) * (1.0 + 1e-9) * weigher.bound(lo, hi) <= tol_px)
                    continue;
            }
            if (n.d < level) {
                const std::uint32_t ci = lay.x.first_child(n.d, n.i);
                const std::uint32_t cj = lay.y.first_child(n.d, n.j);
                for (std::uint32_t a = 0; a < (x1 - x0 >= 2 ? 2u : 1u); ++a)
                    for (std::uint32_t c = 0; c < (y1 - y0 >= 2 ? 2u : 1u); ++c)
                        stack.push_back({n.d + 1, ci + a, cj + c});
                continue;
            }
            std::uint8_t &need = out.needed[std::size_t(n.j) * lay.x.count(level) + n.i];
            if (need)
                continue;
            const auto c0 = std::uint32_t(std::max(double(x0), std::ceil(face.lo.x - 1e-6)));
            const auto c1 = std::uint32_t(std::min(double(x1), std::floor(face.hi.x + 1e-6)));
            const auto r0 = std::uint32_t(std::max(double(y0), std::ceil(face.lo.y - 1e-6)));
            const auto r1 = std::uint32_t(std::min(double(y1), std::floor(face.hi.y + 1e-6)));
            for (std::uint32_t r = r0; r <= r1 && !need; ++r)
                for (std::uint32_t c = c0; c <= c1 && !need; ++c)
                    need = face.holds(c, r);
            out.count += need;
        }
    }
    return out;
}

} // namespace tinlod
