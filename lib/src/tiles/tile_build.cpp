// One quantized-mesh tile from the lattice (tiles.hpp: build_tile): the edges, simplified once from
// their own samples; the interior, greedy insertion then the node erase on the lattice posts at
// least one u/v unit inside the tile; the strip that joins them; quantization; the measure at every
// covered post inside the tile as a decoder reads it.
//
// Heights are quantized on a grid every tile of a level shares: a step of 2^j times the level's
// base step (a power of two near 1/512 of its error), j chosen from the tile's heights, and a
// header range of D steps with D a divisor of 32767, so a height on the step is an exact code. An
// edge vertex takes the coarser step of the tiles that share it (two, four at a corner), so both
// decode it to the same height.
#include "../triangle_plane.hpp"
#include "geodesy.hpp"
#include "post_range.hpp"
#include "tile_measure.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/error.hpp"
#include "tinlod/greedy.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/tiles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

namespace tinlod {

using tiles::Assembly;
using tiles::k_quantized_max;
using tiles::Measure;
using tiles::Quantized;
using tiles::TriangleError;
using tiles::Vertex;

namespace {

// Share of the level's error the edges and the interior are built to: k_chord_share of the rest is
// for the triangles drawn flat, the rest for the u/v rounding of the vertices. The measure after
// quantization checks the sum: every post within the error of the tile as CesiumJS draws it.
constexpr double k_build_share = 7.0 / 8.0;
// A post within this many u/v units of an edge counts as on it (so no vertex rounds onto the edge
// from inside it); the interior starts past it.
constexpr double k_snap_units = 1.0;
// The interior lattice holds at most this many posts across a tile: coarser levels take every
// 2^k-th post (the measure covers the posts left out).
constexpr double k_max_posts_across = 1024.0;
// CesiumJS draws a tile's triangles flat between their Earth-centred vertices, under the surface
// the tile's u/v/height describes by up to R theta^2 / 6 (theta the longest edge's arc, R the
// ellipsoid's largest radius of curvature): no triangle's edge spans more than keeps that within
// this share of the level's error (on coarse levels, a few triangles across a hemisphere would cut
// through the Earth).
constexpr double k_chord_share = 1.0 / 16.0;

double tile_size(int z) { return 180.0 / std::ldexp(1.0, z); }

// The height step of level z: a power of two at most error / 512 (exact in float, as the
// header's heights must be).
double level_step(int z) { return std::exp2(std::floor(std::log2(level_error(z) / 512.0))); }

// A header's range is a divisor of 32767 of steps, so that every whole step is an exact code.
constexpr std::array<int, 8> k_divisors{1, 7, 31, 151, 217, 1057, 4681, 32767};

// The smallest divisor of 32767 at least n, or 0.
int divisor_at_least(double n) {
    for (const int d : k_divisors)
        if (d >= n)
            return d;
    return 0;
}

// The tile's step exponent j (step 2^j * level_step): among those whose step spans its heights
// in half the codes (room for the edges' coarser rounding) and is at most error / 64 (unless the
// first that spans them is coarser), the one whose header range is the tightest (the divisors of
// 32767 are sparse: a finer step can need a far wider range). A function of the range alone: the
// neighbours compute it too.
int range_exponent(const HeightRange &r, int z) {
    const auto steps = [&](int j) {
        const double s = std::ldexp(level_step(z), j);
        return std::ceil(r.hi / s) - std::floor(r.lo / s);
    };
    int first = 0;
    while (steps(first) > 16383.0 && first < 60)
        ++first;
    int best = first;
    double tightest = INFINITY;
    for (int j = first; j <= std::max(first, 3); ++j) {
        // Two steps of room for the edges' rounding.
        const int d = divisor_at_least(steps(j) + 2.0);
        const double span = std::ldexp(double(d), j);
        if (d > 0 && span < tightest)
            tightest = span, best = j;
    }
    return best;
}

// Which way a thread's next pass over a tile's bands runs: north and south by turns, so that a
// pass starts among the bands the last one left in the cache (a coarse tile's bands outnumber
// what the cache holds: passes one way only would read every band again each time).
thread_local bool t_southward = false;

} // namespace

bool tiles::next_pass_southward() { return t_southward = !t_southward; }

namespace {

// Posts a tile reads before it meshes, gathered in one pass over its bands on a lattice read by
// windows: the lattice columns under its vertical edges, the rows under its horizontal ones, and
// its interior's lines at the first stride. Any other post is read from the lattice.
class PostMemo {
  public:
    // Posts [i0, i1] x [j0, j1], clipped to the lattice.
    PostMemo(const GeoLattice &g, std::int64_t i0, std::int64_t i1, std::int64_t j0,
             std::int64_t j1)
        : g_(g), i0_(std::max<std::int64_t>(i0, 0)), i1_(std::min<std::int64_t>(i1, g.width - 1)),
          j0_(std::max<std::int64_t>(j0, 0)), j1_(std::min<std::int64_t>(j1, g.height - 1)) {}

    void add_column(std::int64_t i) {
        if (i >= i0_ && i <= i1_ && j0_ <= j1_)
            columns_.emplace_back(i, std::vector<float>(std::size_t(j1_ - j0_ + 1)));
    }
    void add_row(std::int64_t j) {
        if (j >= j0_ && j <= j1_ && i0_ <= i1_)
            rows_.emplace_back(j, std::vector<float>(std::size_t(i1_ - i0_ + 1)));
    }
    // Columns first_c + k * stride (k < count_c) on rows first_r + k * stride (k < count_r).
    void add_grid(std::int64_t first_c, std::int64_t count_c, std::int64_t first_r,
                  std::int64_t count_r, std::int64_t stride) {
        grid_c_ = first_c, grid_r_ = first_r, count_c_ = count_c, count_r_ = count_r;
        stride_ = stride;
        grid_.resize(std::size_t(count_c * count_r));
    }

    void gather(bool southward) {
        for (std::int64_t n = 0; n <= j1_ - j0_; ++n) {
            const std::int64_t j = southward ? j1_ - n : j0_ + n;
            for (auto &[i, z] : columns_)
                z[std::size_t(j - j0_)] = g_.at(i, j);
            for (auto &[r, z] : rows_)
                if (r == j)
                    for (std::int64_t i = i0_; i <= i1_; ++i)
                        z[std::size_t(i - i0_)] = g_.at(i, j);
            const std::int64_t k = grid_index(j, grid_r_, count_r_);
            for (std::int64_t c = 0; k >= 0 && c < count_c_; ++c)
                grid_[std::size_t(k * count_c_ + c)] = g_.at(grid_c_ + c * stride_, j);
        }
    }

    float at(std::int64_t i, std::int64_t j) const {
        if (i >= i0_ && i <= i1_ && j >= j0_ && j <= j1_) {
            const std::int64_t c = grid_index(i, grid_c_, count_c_),
                               r = grid_index(j, grid_r_, count_r_);
            if (c >= 0 && r >= 0)
                return grid_[std::size_t(r * count_c_ + c)];
            for (const auto &[col, z] : columns_)
                if (col == i)
                    return z[std::size_t(j - j0_)];
            for (const auto &[row, z] : rows_)
                if (row == j)
                    return z[std::size_t(i - i0_)];
        }
        return g_.at(i, j);
    }

  private:
    // The grid line x is on (first + k * stride), or -1.
    std::int64_t grid_index(std::int64_t x, std::int64_t first, std::int64_t count) const {
        const std::int64_t d = x - first;
        return d >= 0 && d % stride_ == 0 && d / stride_ < count ? d / stride_ : -1;
    }

    const GeoLattice &g_;
    std::int64_t i0_, i1_, j0_, j1_;
    std::vector<std::pair<std::int64_t, std::vector<float>>> columns_, rows_;
    std::int64_t grid_c_ = 0, grid_r_ = 0, count_c_ = 0, count_r_ = 0, stride_ = 1;
    std::vector<float> grid_;
};

// A height of the lattice's surface: the post's, or the fill height outside the coverage.
struct Surface {
    const GeoLattice &g;
    double fill;
    const PostMemo *memo = nullptr;
    double at(std::int64_t i, std::int64_t j) const {
        const float h = memo ? memo->at(i, j) : g.at(i, j);
        return std::isnan(h) ? fill : double(h);
    }
};

// Where an edge line stands among the lattice's columns (or rows): on post line `i` (within
// k_snap_units of it), or between `i` and `i + 1` at `t`.
struct LineSpec {
    std::int64_t i = 0;
    double t = 0.0;
    bool snapped = false;
};

} // namespace

// Both tiles that share an edge call it with the same doubles.
double tiles::offset_units(double origin, double step, std::int64_t i, double edge, int z) {
    return (origin + double(i) * step - edge) / tile_size(z) * double(k_quantized_max);
}

namespace {

using tiles::next_pass_southward;
using tiles::offset_units;

LineSpec line_spec(double origin, double step, double edge, int z) {
    const double f = (edge - origin) / step;
    LineSpec s;
    s.i = std::int64_t(std::llround(f));
    if (std::abs(offset_units(origin, step, s.i, edge, z)) < k_snap_units) {
        s.snapped = true;
        return s;
    }
    s.i = std::int64_t(std::floor(f));
    s.t = f - double(s.i);
    return s;
}

// The surface along a vertical line (column spec) at row j, or along a horizontal one at column i.
double along_column(const Surface &s, const LineSpec &c, std::int64_t j) {
    return c.snapped ? s.at(c.i, j) : (1.0 - c.t) * s.at(c.i, j) + c.t * s.at(c.i + 1, j);
}
double along_row(const Surface &s, const LineSpec &r, std::int64_t i) {
    return r.snapped ? s.at(i, r.i) : (1.0 - r.t) * s.at(i, r.i) + r.t * s.at(i, r.i + 1);
}

// The surface at a tile corner: one function for the four tiles that share it.
double corner_height(const Surface &s, double lon, double lat, int z) {
    const LineSpec c = line_spec(s.g.lon0, s.g.dlon, lon, z);
    const LineSpec r = line_spec(s.g.lat0, s.g.dlat, lat, z);
    if (r.snapped)
        return along_column(s, c, r.i);
    return (1.0 - r.t) * along_column(s, c, r.i) + r.t * along_column(s, c, r.i + 1);
}

// A point of an edge's profile: its place along the edge in u/v units (0 .. 32767) and height.
struct EdgePoint {
    double t = 0.0;
    double h = 0.0;
};

// An edge's own samples, from its start corner to its end corner: the lattice interpolated along
// the edge line at every post line that crosses it, not snapped onto either corner. Past the
// lattice (and one line beyond it) the profile is the fill height: those lines are left out.
std::vector<EdgePoint> edge_profile(const Surface &s, bool vertical, double at, double from,
                                    double to, int z) {
    const GeoLattice &g = s.g;
    const double origin = vertical ? g.lat0 : g.lon0, step = vertical ? g.dlat : g.dlon;
    const std::int64_t count = vertical ? g.height : g.width;
    const LineSpec across =
        vertical ? line_spec(g.lon0, g.dlon, at, z) : line_spec(g.lat0, g.dlat, at, z);
    const double start = vertical ? corner_height(s, at, from, z) : corner_height(s, from, at, z);
    const double end = vertical ? corner_height(s, at, to, z) : corner_height(s, to, at, z);
    std::vector<EdgePoint> out{{0.0, start}};
    const std::int64_t lo =
        std::max<std::int64_t>(-1, std::int64_t(std::floor((from - origin) / step)));
    const std::int64_t hi =
        std::min<std::int64_t>(count, std::int64_t(std::ceil((to - origin) / step)));
    for (std::int64_t k = lo; k <= hi; ++k) {
        const double a = offset_units(origin, step, k, from, z);
        const double b = offset_units(origin, step, k, to, z);
        if (!(a >= k_snap_units) || !(b <= -k_snap_units))
            continue;
        out.push_back({a, vertical ? along_column(s, across, k) : along_row(s, across, k)});
    }
    out.push_back({double(k_quantized_max), end});
    return out;
}

// The edge's vertices: the profile simplified by splitting at the farthest sample (Douglas and
// Peucker) until every sample is within `bound` of the polyline through the kept points as a
// decoder reads them (places rounded to the u/v grid, heights to `step`, the corners' to theirs).
// A sample that rounds to the place of an end of its span is never kept (two vertices at one
// place).
struct EdgeVertex {
    int t = 0;      // place along the edge, u/v units
    double h = 0.0; // height, a multiple of the edge's step
};
std::vector<EdgeVertex> simplify_edge(const std::vector<EdgePoint> &p, double bound, double step,
                                      double start_step, double end_step) {
    const auto place = [&](std::size_t k) { return int(std::llround(p[k].t)); };
    const auto height = [&](std::size_t k) {
        const double s = k == 0 ? start_step : k + 1 == p.size() ? end_step : step;
        return std::floor(p[k].h / s + 0.5) * s;
    };
    std::vector<std::uint8_t> keep(p.size(), 0);
    keep.front() = keep.back() = 1;
    std::vector<std::pair<std::size_t, std::size_t>> spans{{0, p.size() - 1}};
    while (!spans.empty()) {
        const auto [a, b] = spans.back();
        spans.pop_back();
        const double ta = place(a), tb = place(b), ha = height(a), hb = height(b);
        double worst = bound;
        std::size_t at = 0;
        for (std::size_t k = a + 1; k < b; ++k) {
            const int t = place(k);
            if (t == int(ta) || t == int(tb))
                continue;
            const double d = std::abs(ha + (p[k].t - ta) / (tb - ta) * (hb - ha) - p[k].h);
            if (d > worst)
                worst = d, at = k;
        }
        if (at == 0)
            continue;
        keep[at] = 1;
        spans.push_back({a, at});
        spans.push_back({at, b});
    }
    std::vector<EdgeVertex> out;
    for (std::size_t k = 0; k < p.size(); ++k)
        if (keep[k])
            out.push_back({place(k), height(k)});
    return out;
}

// The posts of one axis that lie inside the tile at least k_snap_units from both edges, on
// multiples of `stride`: the interior lattice's lines, clipped to the lattice and one line of fill
// beyond it (the rest of the tile there is flat fill), and at least 2.
struct AxisLines {
    std::int64_t first = 0, count = 0, stride = 1;
    std::int64_t at(std::int64_t k) const { return first + k * stride; }
};
AxisLines interior_lines(double origin, double step, std::int64_t posts, double lo, double hi,
                         int z, std::int64_t stride) {
    std::int64_t a = std::int64_t(std::floor((lo - origin) / step)) - 1;
    while (!(offset_units(origin, step, a, lo, z) >= k_snap_units))
        ++a;
    std::int64_t b = std::int64_t(std::ceil((hi - origin) / step)) + 1;
    while (!(offset_units(origin, step, b, hi, z) <= -k_snap_units))
        --b;
    const auto up = [&](std::int64_t x) {
        return x >= 0 ? (x + stride - 1) / stride * stride : -((-x) / stride * stride);
    };
    const auto down = [&](std::int64_t x) {
        return x >= 0 ? x / stride * stride : -((-x + stride - 1) / stride * stride);
    };
    const std::int64_t in_lo = up(a), in_hi = down(b);
    AxisLines l;
    l.stride = stride;
    if (in_hi - in_lo < stride)
        return l; // fewer than 2 lines: the caller takes a finer stride
    std::int64_t lo_line = std::max(in_lo, down(-1)), hi_line = std::min(in_hi, up(posts));
    if (hi_line - lo_line < stride) {
        // The coverage meets the tile only at one side (or just beyond it): two lines there.
        if (up(posts) <= in_lo + stride)
            lo_line = in_lo, hi_line = in_lo + stride;
        else
            lo_line = in_hi - stride, hi_line = in_hi;
    }
    l.first = lo_line;
    l.count = (hi_line - lo_line) / stride + 1;
    return l;
}

// The interior TIN over the window: greedy insertion to the bound, then the node erase (vertical
// model) of its nodes over every post of the window. Returns the window's (c, r) per vertex and
// the triangles, counter-clockwise.
struct InteriorTin {
    std::vector<std::pair<int, int>> nodes;
    std::vector<std::uint32_t> triangles;
};
InteriorTin interior_tin(const Heightfield &win, double bound) {
    GreedyOptions go;
    go.max_error = bound;
    // From the window's corners (no seed grid): the erase would spend more on dropping a seed's
    // nodes than the insertion saves on its first scans.
    go.seed_step = 0;
    go.slope_margin = std::sqrt(0.5); // a vertex moves by up to half a unit in u and v
    const GreedyTin greedy = greedy_tin(win, go);
    Mesh mesh = to_sparse_lattice_mesh(greedy.tin, win);
    EraseOptions eo;
    eo.tolerance = bound;
    eo.lattice = &win;
    {
        NodeEraser eraser(mesh, Significance::vertical(), eo);
        eraser.erase();
    }
    const Mesh tin = live_copy(mesh);
    const auto origin = find_origin_property(tin);
    InteriorTin out;
    for (const auto v : tin.vertices()) {
        const std::int64_t id = tin.property(origin, v);
        out.nodes.emplace_back(int(id % win.width), int(id / win.width));
    }
    for (const auto f : tin.faces())
        for (const auto v : tin.fv_range(f))
            out.triangles.push_back(std::uint32_t(v.idx()));
    return out;
}

// Joins two chains of vertices on parallel lines (the tile edge's and the interior outline's, each
// ordered along `key`) with triangles, advancing the chain whose next vertex comes first.
void zip(const std::vector<std::uint32_t> &outer, const std::vector<std::uint32_t> &inner,
         bool by_v, Assembly &a) {
    const auto key = [&](std::uint32_t k) { return by_v ? a.vertices[k].v : a.vertices[k].u; };
    std::size_t i = 0, j = 0;
    while (i + 1 < outer.size() || j + 1 < inner.size()) {
        std::array<std::uint32_t, 3> t{};
        if (j + 1 == inner.size() ||
            (i + 1 < outer.size() && key(outer[i + 1]) <= key(inner[j + 1]))) {
            t = {outer[i], outer[i + 1], inner[j]};
            ++i;
        } else {
            t = {outer[i], inner[j + 1], inner[j]};
            ++j;
        }
        const Vertex &p = a.vertices[t[0]], &q = a.vertices[t[1]], &r = a.vertices[t[2]];
        const std::int64_t area2 =
            std::int64_t(q.u - p.u) * (r.v - p.v) - std::int64_t(q.v - p.v) * (r.u - p.u);
        if (area2 < 0)
            std::swap(t[1], t[2]);
        a.triangles.insert(a.triangles.end(), t.begin(), t.end());
    }
}

// The longest edge, in u/v units, of a level-z triangle whose chord is within k_chord_share of the
// level's error.
double max_edge_units(int z) {
    const double radius = tiles::k_wgs84_a * tiles::k_wgs84_a / tiles::k_wgs84_b;
    const double arc = std::sqrt(6.0 * k_chord_share * level_error(z) / radius);
    return arc / (tile_size(z) * M_PI / 180.0) * double(k_quantized_max);
}

// Splits every edge longer than `max_len` u/v units at its midpoint (the triangles round it: one,
// two or three split edges) until none is. A tile edge's segment splits by its own length and
// ends, so the tiles that share it split it alike; its midpoints take the edge's step, `edge_step`
// (west, south, east, north), others the tile's `step`. A midpoint of a segment across the tile
// that rounds onto a tile edge moves one unit inside.
void split_long_edges(Assembly &a, double max_len, const std::array<double, 4> &edge_step,
                      double step) {
    const auto on_edge = [](int u, int v) {
        return u == 0 ? 0 : v == 0 ? 1 : u == k_quantized_max ? 2 : v == k_quantized_max ? 3 : -1;
    };
    const auto along_edge = [](const Vertex &p, const Vertex &q) {
        return (p.u == q.u && (p.u == 0 || p.u == k_quantized_max)) ||
               (p.v == q.v && (p.v == 0 || p.v == k_quantized_max));
    };
    for (;;) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mids;
        const auto mid = [&](std::uint32_t i, std::uint32_t j) -> std::int64_t {
            const Vertex p = a.vertices[i], q = a.vertices[j];
            if (std::hypot(double(p.u - q.u), double(p.v - q.v)) <= max_len)
                return -1;
            const std::pair<std::uint32_t, std::uint32_t> key{std::min(i, j), std::max(i, j)};
            if (const auto it = mids.find(key); it != mids.end())
                return it->second;
            Vertex m{(p.u + q.u) / 2, (p.v + q.v) / 2, 0.0};
            if (!along_edge(p, q)) {
                m.u = std::clamp(m.u, 1, k_quantized_max - 1);
                m.v = std::clamp(m.v, 1, k_quantized_max - 1);
            }
            const int e = on_edge(m.u, m.v);
            const double s = e < 0 ? step : edge_step[std::size_t(e)];
            m.h = std::floor((p.h + q.h) / 2.0 / s + 0.5) * s;
            mids[key] = std::uint32_t(a.vertices.size());
            a.vertices.push_back(m);
            return mids[key];
        };
        std::vector<std::uint32_t> out;
        const auto add = [&out](std::uint32_t p, std::uint32_t q, std::uint32_t r) {
            out.insert(out.end(), {p, q, r});
        };
        for (std::size_t t = 0; t < a.triangles.size(); t += 3) {
            std::array<std::uint32_t, 3> c{a.triangles[t], a.triangles[t + 1], a.triangles[t + 2]};
            std::array<std::int64_t, 3> m{mid(c[0], c[1]), mid(c[1], c[2]), mid(c[2], c[0])};
            const int splits = int(m[0] >= 0) + int(m[1] >= 0) + int(m[2] >= 0);
            // Turn the triangle so that its split edges come first (m[0], then m[1]).
            for (int turn = 0; turn < 3 && splits < 3; ++turn) {
                if (m[0] >= 0 && (splits == 1 || m[1] >= 0))
                    break;
                std::rotate(c.begin(), c.begin() + 1, c.end());
                std::rotate(m.begin(), m.begin() + 1, m.end());
            }
            const auto m0 = std::uint32_t(m[0]), m1 = std::uint32_t(m[1]), m2 = std::uint32_t(m[2]);
            if (splits == 0) {
                add(c[0], c[1], c[2]);
            } else if (splits == 1) {
                add(c[0], m0, c[2]), add(m0, c[1], c[2]);
            } else if (splits == 2) {
                add(m0, c[1], m1), add(c[0], m0, m1), add(c[0], m1, c[2]);
            } else {
                add(c[0], m0, m2), add(m0, c[1], m1), add(m2, m1, c[2]), add(m0, m1, m2);
            }
        }
        a.triangles = std::move(out);
        if (mids.empty())
            return;
    }
}

Quantized quantize(const std::vector<Vertex> &vs, const HeightRange &range, double step) {
    double lo = range.lo, hi = range.hi;
    for (const Vertex &v : vs)
        lo = std::min(lo, v.h), hi = std::max(hi, v.h);
    Quantized q;
    q.step = step;
    q.min_h = std::floor(lo / step) * step;
    // Past 32767 steps (an edge rounded to a far coarser neighbour's step) the codes clamp, and
    // the measure sees it.
    const int needed = divisor_at_least(std::ceil((hi - q.min_h) / step));
    q.divisor = needed > 0 ? needed : k_quantized_max;
    q.max_h = q.min_h + double(q.divisor) * step;
    for (const Vertex &v : vs)
        q.codes.push_back(q.code(v.h));
    return q;
}

// The unit normal of the DEM at a place, from central differences of the nearest post's
// neighbours (the fill height outside the coverage), in the Earth-centred frame.
glm::dvec3 dem_normal(const Surface &s, double lon, double lat) {
    const GeoLattice &g = s.g;
    const auto i = std::int64_t(std::llround((lon - g.lon0) / g.dlon));
    const auto j = std::int64_t(std::llround((lat - g.lat0) / g.dlat));
    const double p = lat * M_PI / 180.0;
    const double e2 =
        1.0 - (tiles::k_wgs84_b * tiles::k_wgs84_b) / (tiles::k_wgs84_a * tiles::k_wgs84_a);
    const double w = 1.0 - e2 * std::sin(p) * std::sin(p);
    const double east = g.dlon * M_PI / 180.0 * tiles::k_wgs84_a / std::sqrt(w) * std::cos(p);
    const double north = g.dlat * M_PI / 180.0 * tiles::k_wgs84_a * (1.0 - e2) / (w * std::sqrt(w));
    const double gx = (s.at(i + 1, j) - s.at(i - 1, j)) / (2.0 * std::max(east, 1e-3));
    const double gy = (s.at(i, j + 1) - s.at(i, j - 1)) / (2.0 * north);
    const auto frame = tiles::enu_frame(lon, lat);
    return glm::normalize(-gx * frame[0] - gy * frame[1] + frame[2]);
}

} // namespace

namespace tiles {

namespace {

// The posts of a tile and the next beyond each edge: [i0, i1] x [j0, j1], unclipped.
std::array<std::int64_t, 4> post_box(const GeoLattice &g, const TileId &tile) {
    const GeoRect rect = tile_rect(tile);
    return {std::int64_t(std::ceil((rect.west - g.lon0) / g.dlon)) - 1,
            std::int64_t(std::floor((rect.east - g.lon0) / g.dlon)) + 1,
            std::int64_t(std::ceil((rect.south - g.lat0) / g.dlat)) - 1,
            std::int64_t(std::floor((rect.north - g.lat0) / g.dlat)) + 1};
}

} // namespace

PostRange tile_post_range(const GeoLattice &g, const TileId &tile) {
    const auto [i0, i1, j0, j1] = post_box(g, tile);
    PostRange r;
    r.fill = i0 < 0 || j0 < 0 || i1 >= g.width || j1 >= g.height;
    for (std::int64_t j = std::max<std::int64_t>(j0, 0);
         j <= std::min<std::int64_t>(j1, g.height - 1); ++j)
        for (std::int64_t i = std::max<std::int64_t>(i0, 0);
             i <= std::min<std::int64_t>(i1, g.width - 1); ++i) {
            const float h = g.at(i, j);
            if (std::isnan(h)) {
                r.fill = true;
                continue;
            }
            r.covered = true;
            r.lo = std::min(r.lo, double(h)), r.hi = std::max(r.hi, double(h));
        }
    return r;
}

bool tile_meets_lattice(const GeoLattice &g, const TileId &tile) {
    const auto [i0, i1, j0, j1] = post_box(g, tile);
    return i1 >= 0 && i0 < g.width && j1 >= 0 && j0 < g.height;
}

HeightRange with_fill(const PostRange &p, const TileOptions &options) {
    HeightRange r{p.lo, p.hi, p.covered};
    if (p.fill || !p.covered)
        r.lo = std::min(r.lo, options.fill_height), r.hi = std::max(r.hi, options.fill_height);
    return r;
}

} // namespace tiles

HeightRange tile_height_range(const GeoLattice &g, const TileId &tile, const TileOptions &options) {
    return tiles::with_fill(tiles::tile_post_range(g, tile), options);
}

TileMesh build_tile(const GeoLattice &g, const TileId &id, const TileOptions &options,
                    const RangeOf &range_of) {
    const int z = id.z;
    const std::int64_t nx = std::int64_t(2) << z, ny = std::int64_t(1) << z;
    const auto range = [&](std::int64_t dx, std::int64_t dy) -> HeightRange {
        const TileId n{z, ((id.x + dx) % nx + nx) % nx, id.y + dy};
        if (n.y < 0 || n.y >= ny)
            return {0.0, 0.0, false};
        return range_of ? range_of(n) : tile_height_range(g, n, options);
    };
    // The step exponent of this tile and of its eight neighbours ([dy + 1][dx + 1]).
    std::array<std::array<int, 3>, 3> j{};
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            j[std::size_t(dy + 1)][std::size_t(dx + 1)] = range_exponent(range(dx, dy), z);
    const HeightRange own = range(0, 0);
    const double base = level_step(z), step = std::ldexp(base, j[1][1]);
    const auto coarsest = [&](std::initializer_list<std::pair<int, int>> tiles) {
        int e = 0;
        for (const auto &[dx, dy] : tiles)
            e = std::max(e, j[std::size_t(dy + 1)][std::size_t(dx + 1)]);
        return std::ldexp(base, e);
    };
    const double bound = level_error(z);
    const GeoRect rect = tile_rect(id);
    const double u_per_lon = double(k_quantized_max) / tile_size(z);
    std::int64_t stride = 1;
    while (tile_size(z) / (double(stride) * std::min(g.dlon, g.dlat)) > k_max_posts_across)
        stride *= 2;
    // The interior's lattice lines at `stride`, a finer one while fewer than 2 fit.
    AxisLines cols, rows;
    const auto interior_axes = [&] {
        for (;;) {
            cols = interior_lines(g.lon0, g.dlon, g.width, rect.west, rect.east, z, stride);
            rows = interior_lines(g.lat0, g.dlat, g.height, rect.south, rect.north, z, stride);
            if ((cols.count >= 2 && rows.count >= 2) || stride == 1)
                break;
            stride /= 2;
        }
    };
    interior_axes();
    // On a lattice read by windows, what the edges and the first interior read, in one pass over
    // the tile's bands (a coarse tile's bands do not stay in the cache from one pass to the next).
    PostMemo memo(g, std::int64_t(std::floor((rect.west - g.lon0) / g.dlon)) - 2,
                  std::int64_t(std::ceil((rect.east - g.lon0) / g.dlon)) + 2,
                  std::int64_t(std::floor((rect.south - g.lat0) / g.dlat)) - 2,
                  std::int64_t(std::ceil((rect.north - g.lat0) / g.dlat)) + 2);
    if (g.bands) {
        for (const double lon : {rect.west, rect.east}) {
            const LineSpec c = line_spec(g.lon0, g.dlon, lon, z);
            memo.add_column(c.i);
            if (!c.snapped)
                memo.add_column(c.i + 1);
        }
        for (const double lat : {rect.south, rect.north}) {
            const LineSpec r = line_spec(g.lat0, g.dlat, lat, z);
            memo.add_row(r.i);
            if (!r.snapped)
                memo.add_row(r.i + 1);
        }
        if (own.covered && cols.count >= 2 && rows.count >= 2)
            memo.add_grid(cols.first, cols.count, rows.first, rows.count, stride);
        memo.gather(next_pass_southward());
    }
    const Surface surface{g, options.fill_height, g.bands ? &memo : nullptr};

    // The four edges, from their own samples only: west and east run north, south and north east.
    struct EdgeDef {
        bool vertical;
        double at, from, to;
        std::pair<int, int> across;                   // the neighbour sharing it
        std::pair<int, int> start_corner, end_corner; // the diagonal neighbours at its ends
    };
    const std::array<EdgeDef, 4> defs{
        {{true, rect.west, rect.south, rect.north, {-1, 0}, {-1, -1}, {-1, 1}},
         {false, rect.south, rect.west, rect.east, {0, -1}, {-1, -1}, {1, -1}},
         {true, rect.east, rect.south, rect.north, {1, 0}, {1, -1}, {1, 1}},
         {false, rect.north, rect.west, rect.east, {0, 1}, {-1, 1}, {1, 1}}}};
    std::array<std::vector<EdgeVertex>, 4> edge_vertices;
    std::array<double, 4> edge_step{};
    for (std::size_t e = 0; e < 4; ++e) {
        const EdgeDef &d = defs[e];
        const auto [ax, ay] = d.across;
        // The edge takes the coarser step of its two tiles, a corner the coarsest of its four.
        const auto corner_step = [&](std::pair<int, int> diag) {
            return coarsest({{0, 0}, {ax, ay}, diag, {diag.first - ax, diag.second - ay}});
        };
        edge_step[e] = coarsest({{0, 0}, {ax, ay}});
        edge_vertices[e] = simplify_edge(edge_profile(surface, d.vertical, d.at, d.from, d.to, z),
                                         k_build_share * bound, edge_step[e],
                                         corner_step(d.start_corner), corner_step(d.end_corner));
    }

    double interior_bound = k_build_share * bound - step / 2.0;

    // A tile over no DEM (only level 0 writes one) is flat fill: its square, which the split
    // into short edges makes a regular grid.
    const bool bare = !own.covered && std::all_of(edge_vertices.begin(), edge_vertices.end(),
                                                  [](const auto &ev) { return ev.size() == 2; });
    // The interior's lattice at `stride`, read again only when a rebuild takes a finer one.
    Heightfield win;
    const auto read_interior = [&] {
        interior_axes();
        if (cols.count < 2 || rows.count < 2)
            throw Error(
                "tile " + std::to_string(z) + "/" + std::to_string(id.x) + "/" +
                    std::to_string(id.y),
                "narrower than 2 DEM posts inside: the level is beyond the DEM's resolution");
        win.width = int(cols.count), win.height = int(rows.count);
        win.dx = double(stride) * g.dlon * u_per_lon;
        win.dy = double(stride) * g.dlat * u_per_lon;
        win.z.resize(std::size_t(win.width) * std::size_t(win.height));
        const bool southward = next_pass_southward();
        for (int n = 0; n < win.height; ++n) {
            const int r = southward ? win.height - 1 - n : n;
            for (int c = 0; c < win.width; ++c)
                win.at(c, r) = float(surface.at(cols.at(c), rows.at(r)));
        }
    };
    if (!bare)
        read_interior();
    TileMesh best;
    best.error_ratio = INFINITY;
    std::int64_t best_flipped = std::numeric_limits<std::int64_t>::max();
    for (int attempt = 0; attempt < 8; ++attempt) {
        Assembly a;
        // Corners first (SW, SE, NE, NW), then each edge's inner vertices.
        const std::array<std::array<int, 2>, 4> corner_uv{{{0, 0},
                                                           {k_quantized_max, 0},
                                                           {k_quantized_max, k_quantized_max},
                                                           {0, k_quantized_max}}};
        const std::array<double, 4> corner_h{edge_vertices[0].front().h, edge_vertices[2].front().h,
                                             edge_vertices[2].back().h, edge_vertices[0].back().h};
        for (int k = 0; k < 4; ++k)
            a.vertices.push_back({corner_uv[std::size_t(k)][0], corner_uv[std::size_t(k)][1],
                                  corner_h[std::size_t(k)]});
        // Corner ids at each edge's start and end (west: SW..NW, south: SW..SE, east: SE..NE,
        // north: NW..NE).
        const std::array<std::pair<std::uint32_t, std::uint32_t>, 4> ends{
            {{0, 3}, {0, 1}, {1, 2}, {3, 2}}};
        std::array<std::vector<std::uint32_t>, 4> outer;
        for (std::size_t e = 0; e < 4; ++e) {
            outer[e].push_back(ends[e].first);
            const auto &ev = edge_vertices[e];
            for (std::size_t k = 1; k + 1 < ev.size(); ++k) {
                Vertex v;
                v.h = ev[k].h;
                const int fixed = e == 2 || e == 3 ? k_quantized_max : 0;
                v.u = defs[e].vertical ? fixed : ev[k].t;
                v.v = defs[e].vertical ? ev[k].t : fixed;
                outer[e].push_back(std::uint32_t(a.vertices.size()));
                a.vertices.push_back(v);
            }
            outer[e].push_back(ends[e].second);
        }
        if (bare) {
            a.triangles = {0, 1, 2, 0, 2, 3};
        } else {
            const InteriorTin inner = interior_tin(win, std::max(interior_bound, 1e-6 * bound));

            // The interior's vertices, and its outline as four chains.
            const std::uint32_t first_inner = std::uint32_t(a.vertices.size());
            std::array<std::vector<std::pair<int, std::uint32_t>>, 4> sides;
            for (std::size_t k = 0; k < inner.nodes.size(); ++k) {
                const auto [c, r] = inner.nodes[k];
                Vertex v;
                v.u = int(std::llround(offset_units(g.lon0, g.dlon, cols.at(c), rect.west, z)));
                v.v = int(std::llround(offset_units(g.lat0, g.dlat, rows.at(r), rect.south, z)));
                // On the tile's step, within the half step the interior's bound leaves for it.
                v.h = std::floor(win.at(c, r) / step + 0.5) * step;
                const std::uint32_t idx = first_inner + std::uint32_t(k);
                if (c == 0)
                    sides[0].emplace_back(r, idx);
                if (r == 0)
                    sides[1].emplace_back(c, idx);
                if (c == win.width - 1)
                    sides[2].emplace_back(r, idx);
                if (r == win.height - 1)
                    sides[3].emplace_back(c, idx);
                a.vertices.push_back(v);
            }
            for (const std::uint32_t t : inner.triangles)
                a.triangles.push_back(first_inner + t);
            for (std::size_t e = 0; e < 4; ++e) {
                std::sort(sides[e].begin(), sides[e].end());
                std::vector<std::uint32_t> chain;
                for (const auto &s : sides[e])
                    chain.push_back(s.second);
                zip(outer[e], chain, defs[e].vertical, a);
            }
        }

        split_long_edges(a, max_edge_units(z), edge_step, step);
        Quantized q = quantize(a.vertices, own, step);
        std::vector<TriangleError> errors;
        Measure m = measure(g, id, a.vertices, q, a.triangles, {}, bound, errors);
        // Posts over the bound after rounding (most often between the interior's lines on coarse
        // levels): made vertices in place, without a rebuild.
        if (m.flipped == 0 && m.missed == 0 && std::max(m.max_error, m.max_drawn) > bound)
            m = repair(g, id, bound, a, q, errors, m);
        const double worst = std::max(m.max_error, m.max_drawn);
        const double ratio = m.missed > 0 ? INFINITY : worst / bound;
        const bool better =
            m.flipped < best_flipped || (m.flipped == best_flipped && ratio < best.error_ratio);
        if (better || attempt == 0) {
            best = TileMesh{};
            best.id = id;
            for (std::size_t k = 0; k < a.vertices.size(); ++k) {
                best.u.push_back(std::uint16_t(a.vertices[k].u));
                best.v.push_back(std::uint16_t(a.vertices[k].v));
                best.h.push_back(q.codes[k]);
            }
            best.triangles = a.triangles;
            best.min_height = float(q.min_h);
            best.max_height = float(q.max_h);
            best.max_error = worst;
            best.error_ratio = ratio;
            best.samples = m.samples;
            best.repaired = m.inserted;
            best_flipped = m.flipped;
        }
        best.builds = attempt + 1;
        if (m.flipped == 0 && ratio <= 1.0)
            break;
        // A triangle turned over by rounding (or posts the repair could not reach): more nodes (a
        // tighter bound), and every other time a finer stride, only while the interior stays
        // within k_max_posts_across (a tile's work in the memory budget: a coverage that meets the
        // tile in a corner on coarse levels).
        const auto finer_fits = [&](const AxisLines &l) {
            return double(2 * l.count) <= k_max_posts_across;
        };
        if (attempt % 2 == 1 && stride > 1 && !bare && finer_fits(cols) && finer_fits(rows)) {
            stride /= 2;
            read_interior();
        } else {
            interior_bound *= 0.7;
        }
    }

    // Edge lists in CesiumJS's order: west south to north, south east to west, east north to
    // south, north west to east.
    for (std::uint32_t k = 0; k < best.u.size(); ++k) {
        if (best.u[k] == 0)
            best.west.push_back(k);
        if (best.v[k] == 0)
            best.south.push_back(k);
        if (best.u[k] == k_quantized_max)
            best.east.push_back(k);
        if (best.v[k] == k_quantized_max)
            best.north.push_back(k);
    }
    const auto by = [&](const std::vector<std::uint16_t> &key, bool ascending) {
        return [&key, ascending](std::uint32_t p, std::uint32_t q) {
            return ascending ? key[p] < key[q] : key[p] > key[q];
        };
    };
    std::sort(best.west.begin(), best.west.end(), by(best.v, true));
    std::sort(best.south.begin(), best.south.end(), by(best.u, false));
    std::sort(best.east.begin(), best.east.end(), by(best.v, false));
    std::sort(best.north.begin(), best.north.end(), by(best.u, true));

    if (options.normals) {
        // By rows of vertices, one way: a lattice read by windows reads each band once.
        std::vector<std::uint32_t> order(best.u.size());
        for (std::uint32_t k = 0; k < order.size(); ++k)
            order[k] = k;
        const bool southward = next_pass_southward();
        std::stable_sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) {
            return southward ? best.v[p] > best.v[q] : best.v[p] < best.v[q];
        });
        best.normals.resize(2 * best.u.size());
        for (const std::uint32_t k : order) {
            const double lon =
                rect.west + double(best.u[k]) / k_quantized_max * (rect.east - rect.west);
            const double lat =
                rect.south + double(best.v[k]) / k_quantized_max * (rect.north - rect.south);
            const auto oct = tiles::oct_encode(dem_normal(surface, lon, lat));
            best.normals[2 * k] = oct[0];
            best.normals[2 * k + 1] = oct[1];
        }
    }
    return best;
}

} // namespace tinlod
