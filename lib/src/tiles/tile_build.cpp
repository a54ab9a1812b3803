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

using tiles::k_quantized_max;

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
bool next_pass_southward() { return t_southward = !t_southward; }

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

// The offset of lattice line `i` from an edge line at `edge` degrees, in u/v units of level z.
// Both tiles that share the edge call it with the same doubles.
double offset_units(double origin, double step, std::int64_t i, double edge, int z) {
    return (origin + double(i) * step - edge) / tile_size(z) * double(k_quantized_max);
}

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

// A vertex of the tile as it is assembled: its u/v place and its height, a whole multiple of the
// tile's step (an edge's, of a coarser one).
struct Vertex {
    int u = 0, v = 0;
    double h = 0.0;
};

struct Assembly {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> triangles;
};

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

// The tile's heights: the header range and each vertex's code.
struct Quantized {
    double min_h = 0, max_h = 0, step = 0;
    int divisor = k_quantized_max; // the header range in steps
    std::vector<std::uint16_t> codes;
    std::uint16_t code(double h) const {
        const double c = std::round((h - min_h) / step) * double(k_quantized_max / divisor);
        return std::uint16_t(std::clamp(c, 0.0, double(k_quantized_max)));
    }
};
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

double decoded_height(const Quantized &q, std::uint16_t code) {
    return q.min_h + double(code) / double(k_quantized_max) * (q.max_h - q.min_h);
}

// The measure: every covered post inside the tile against the quantized TIN, by rows of posts
// under each triangle, twice: vertically, and as CesiumJS draws the triangle, flat between its
// vertices' Earth-centred positions (the post's distance to the drawn point at its place in the
// triangle, on the drawn surface: so at least its distance to that surface). Counts the triangles
// that rounding turned over (not counter-clockwise).
struct Measure {
    double max_error = 0.0; // vertical
    double max_drawn = 0.0;
    std::int64_t samples = 0;
    std::int64_t flipped = 0;
    std::int64_t missed = 0;   // covered posts inside the tile under no triangle
    std::int64_t inserted = 0; // posts the repair made vertices
};
// One triangle's posts: the largest of each error, and the worst post over the bound that the
// repair can make a vertex (its u/v strictly inside the tile and on none of the triangle's
// vertices), with its error (the larger of both), or 0.
struct TriangleError {
    double error = 0.0, drawn = 0.0, over = 0.0;
    std::int64_t i = 0, j = 0;
};
// Measures the triangles numbered in `which` (all of them when it is empty, and then also the
// samples, the posts under no triangle and the triangles turned over) into `errors`.
Measure measure(const GeoLattice &g, const TileId &id, const std::vector<Vertex> &vs,
                const Quantized &q, const std::vector<std::uint32_t> &triangles,
                const std::vector<std::uint32_t> &which, double bound,
                std::vector<TriangleError> &errors) {
    const GeoRect rect = tile_rect(id);
    const int z = id.z;
    const bool all = which.empty();
    errors.resize(triangles.size() / 3);
    if (all)
        std::fill(errors.begin(), errors.end(), TriangleError{});
    for (const std::uint32_t t : which)
        errors[t] = TriangleError{};
    // Posts inside the tile, clipped to the lattice; their u/v places, exactly as the edges see
    // them.
    std::int64_t i0 =
        std::max<std::int64_t>(0, std::int64_t(std::floor((rect.west - g.lon0) / g.dlon)));
    std::int64_t i1 =
        std::min<std::int64_t>(g.width - 1, std::int64_t(std::ceil((rect.east - g.lon0) / g.dlon)));
    std::int64_t j0 =
        std::max<std::int64_t>(0, std::int64_t(std::floor((rect.south - g.lat0) / g.dlat)));
    std::int64_t j1 = std::min<std::int64_t>(
        g.height - 1, std::int64_t(std::ceil((rect.north - g.lat0) / g.dlat)));
    Measure m;
    if (i1 < i0 || j1 < j0)
        return m;
    std::vector<double> pu(std::size_t(i1 - i0 + 1)), pv(std::size_t(j1 - j0 + 1));
    for (std::int64_t i = i0; i <= i1; ++i)
        pu[std::size_t(i - i0)] = offset_units(g.lon0, g.dlon, i, rect.west, z);
    for (std::int64_t j = j0; j <= j1; ++j)
        pv[std::size_t(j - j0)] = offset_units(g.lat0, g.dlat, j, rect.south, z);
    const auto inside = [](double x) { return x >= 0.0 && x <= double(k_quantized_max); };
    const auto strictly_inside = [](std::int64_t x) { return x >= 1 && x < k_quantized_max; };
    // The posts' Earth-centred frames (tiles::ecef's terms per column and row) and the vertices'
    // positions as decoded.
    const double e2 =
        1.0 - (tiles::k_wgs84_b * tiles::k_wgs84_b) / (tiles::k_wgs84_a * tiles::k_wgs84_a);
    std::vector<glm::dvec2> col_trig(pu.size());
    std::vector<glm::dvec3> row_trig(pv.size());
    for (std::size_t ir = 0; ir < pu.size(); ++ir) {
        const double l = (g.lon0 + double(i0 + std::int64_t(ir)) * g.dlon) * M_PI / 180.0;
        col_trig[ir] = {std::cos(l), std::sin(l)};
    }
    for (std::size_t jr = 0; jr < pv.size(); ++jr) {
        const double p = (g.lat0 + double(j0 + std::int64_t(jr)) * g.dlat) * M_PI / 180.0;
        row_trig[jr] = {std::cos(p), std::sin(p),
                        tiles::k_wgs84_a / std::sqrt(1.0 - e2 * std::sin(p) * std::sin(p))};
    }
    std::vector<glm::dvec3> xyz;
    for (std::size_t k = 0; k < vs.size(); ++k)
        xyz.push_back(
            tiles::ecef(rect.west + double(vs[k].u) / k_quantized_max * (rect.east - rect.west),
                        rect.south + double(vs[k].v) / k_quantized_max * (rect.north - rect.south),
                        decoded_height(q, q.codes[k])));
    constexpr double k_eps = 1e-9;
    const std::size_t count = all ? triangles.size() / 3 : which.size();
    // By bands of rows, the lattice's (one when it is held whole): a lattice read by windows
    // then reads each band once, whatever the order of the triangles.
    const std::int64_t band = g.rows_together();
    const bool southward = next_pass_southward();
    for (std::int64_t n_band = 0; n_band <= j1 / band - j0 / band; ++n_band) {
        const std::int64_t b = southward ? j1 / band - n_band : j0 / band + n_band;
        const std::ptrdiff_t band_lo = std::max<std::ptrdiff_t>(0, b * band - j0),
                             band_hi = std::min<std::ptrdiff_t>(std::ptrdiff_t(pv.size()),
                                                                (b + 1) * band - j0);
        // The band's posts some triangle covers.
        std::vector<bool> seen(all ? std::size_t(band_hi - band_lo) * pu.size() : 0, false);
        for (std::size_t n = 0; n < count; ++n) {
            const std::size_t t = all ? 3 * n : 3 * std::size_t(which[n]);
            TriangleError &te = errors[t / 3];
            std::array<glm::dvec3, 3> c;
            for (int k = 0; k < 3; ++k) {
                const Vertex &v = vs[triangles[t + std::size_t(k)]];
                c[std::size_t(k)] = {double(v.u), double(v.v),
                                     decoded_height(q, q.codes[triangles[t + std::size_t(k)]])};
            }
            const double area2 =
                (c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[1].y - c[0].y) * (c[2].x - c[0].x);
            if (area2 < 0.0 && n_band == 0 && all)
                ++m.flipped;
            if (area2 <= 0.0)
                continue;
            const TrianglePlane plane(c[0], c[1], c[2]);
            const PlaneWeights w =
                plane_weights(glm::dvec2(c[0]), glm::dvec2(c[1]), glm::dvec2(c[2]));
            const glm::dvec3 &xa = xyz[triangles[t]], &xb = xyz[triangles[t + 1]],
                             &xc = xyz[triangles[t + 2]];
            const double vlo = std::min({c[0].y, c[1].y, c[2].y}),
                         vhi = std::max({c[0].y, c[1].y, c[2].y});
            const auto jl =
                std::max(band_lo, std::lower_bound(pv.begin(), pv.end(), vlo - k_eps) - pv.begin());
            const auto jh =
                std::min(band_hi, std::upper_bound(pv.begin(), pv.end(), vhi + k_eps) - pv.begin());
            for (auto jr = jl; jr < jh; ++jr) {
                const double y = pv[std::size_t(jr)];
                if (!inside(y))
                    continue;
                // The triangle's span on this row: the intersections of its edges with the line.
                double ulo = INFINITY, uhi = -INFINITY;
                for (int k = 0; k < 3; ++k) {
                    const glm::dvec3 &p = c[std::size_t(k)], &r = c[std::size_t((k + 1) % 3)];
                    if ((y < std::min(p.y, r.y) - k_eps) || (y > std::max(p.y, r.y) + k_eps))
                        continue;
                    if (p.y == r.y) {
                        ulo = std::min({ulo, p.x, r.x}), uhi = std::max({uhi, p.x, r.x});
                        continue;
                    }
                    const double x =
                        p.x + (std::clamp(y, std::min(p.y, r.y), std::max(p.y, r.y)) - p.y) /
                                  (r.y - p.y) * (r.x - p.x);
                    ulo = std::min(ulo, x), uhi = std::max(uhi, x);
                }
                const auto il = std::lower_bound(pu.begin(), pu.end(), ulo - k_eps) - pu.begin();
                const auto ih = std::upper_bound(pu.begin(), pu.end(), uhi + k_eps) - pu.begin();
                const std::int64_t rv = std::llround(y);
                for (auto ir = il; ir < ih; ++ir) {
                    const double x = pu[std::size_t(ir)];
                    const float h = g.at(i0 + ir, j0 + jr);
                    if (!inside(x) || std::isnan(h))
                        continue;
                    if (all)
                        seen[std::size_t(jr - band_lo) * pu.size() + std::size_t(ir)] = true;
                    const double vertical = std::abs(plane.height(x, y) - double(h));
                    const double wa = glm::dot(w.a, glm::dvec3(x, y, 1.0)),
                                 wb = glm::dot(w.b, glm::dvec3(x, y, 1.0));
                    const glm::dvec2 &cl = col_trig[std::size_t(ir)];
                    const glm::dvec3 &rw = row_trig[std::size_t(jr)];
                    const double up = rw.z + double(h);
                    const glm::dvec3 post{up * rw.x * cl.x, up * rw.x * cl.y,
                                          (rw.z * (1.0 - e2) + double(h)) * rw.y};
                    const double drawn =
                        glm::length(wa * xa + wb * xb + (1.0 - wa - wb) * xc - post);
                    te.error = std::max(te.error, vertical);
                    te.drawn = std::max(te.drawn, drawn);
                    const double worst = std::max(vertical, drawn);
                    if (worst <= bound || worst < te.over)
                        continue;
                    // Of posts equally over, the first from the south-west, whichever way the
                    // bands run.
                    if (worst == te.over && std::pair(j0 + jr, i0 + ir) > std::pair(te.j, te.i))
                        continue;
                    const std::int64_t ru = std::llround(x);
                    const auto at_vertex = [&](const glm::dvec3 &p) {
                        return double(ru) == p.x && double(rv) == p.y;
                    };
                    if (strictly_inside(ru) && strictly_inside(rv) &&
                        !std::any_of(c.begin(), c.end(), at_vertex))
                        te.over = worst, te.i = i0 + ir, te.j = j0 + jr;
                }
            }
        }
        if (!all)
            continue;
        for (auto jr = band_lo; jr < band_hi; ++jr)
            for (std::size_t ir = 0; ir < pu.size(); ++ir)
                if (inside(pu[ir]) && inside(pv[std::size_t(jr)]) &&
                    !std::isnan(g.at(i0 + std::int64_t(ir), j0 + jr))) {
                    ++m.samples;
                    m.missed += seen[std::size_t(jr - band_lo) * pu.size() + ir] ? 0 : 1;
                }
    }
    for (const TriangleError &te : errors)
        m.max_error = std::max(m.max_error, te.error),
        m.max_drawn = std::max(m.max_drawn, te.drawn);
    return m;
}

// The most posts the repair makes vertices in one tile: its work stays within the tile's share
// of the memory budget (some 300 bytes a vertex).
constexpr std::size_t k_max_repairs = std::size_t(1) << 18;
// And the most rounds (a flip can undo another's).
constexpr int k_max_rounds = 256;

// Makes the posts over the bound vertices, the worst under each triangle first, then measures
// again only the triangles that changed, until no post is over (or none over can be a vertex: one
// on a tile edge, or rounding onto a vertex). A post becomes a vertex at its rounded u/v, strictly
// inside the tile (the edges stay as they are: they are their own samples' only), its height on
// the tile's step; the triangle round it splits in three (the two on an edge it rounds onto, in
// two each), then Lawson's flips restore the Delaunay property round it, each over a strictly
// convex quadrilateral, all in exact integer u/v, so no triangle turns over or degenerates.
// Returns the measure of the repaired tile (with the first measure's counts).
Measure repair(const GeoLattice &g, const TileId &id, double bound, Assembly &a, Quantized &q,
               std::vector<TriangleError> &errors, Measure m) {
    __extension__ using Wide = __int128; // incircle's products pass 64 bits
    auto &tr = a.triangles;
    const auto key = [](std::uint32_t p, std::uint32_t r) {
        return (std::uint64_t(p) << 32) | std::uint64_t(r);
    };
    std::unordered_map<std::uint64_t, std::uint32_t> owner; // a directed edge's triangle
    for (std::uint32_t t = 0; 3 * std::size_t(t) < tr.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k)
            owner[key(tr[3 * t + k], tr[3 * t + (k + 1) % 3])] = t;
    std::vector<std::uint32_t> changed;
    std::vector<std::uint8_t> is_changed(tr.size() / 3, 0);
    const auto set = [&](std::uint32_t t, std::uint32_t p0, std::uint32_t p1, std::uint32_t p2) {
        if (3 * std::size_t(t) == tr.size()) {
            tr.insert(tr.end(), {0, 0, 0});
            is_changed.push_back(0);
        }
        for (std::size_t k = 0; k < 3; ++k) {
            const auto it = owner.find(key(tr[3 * t + k], tr[3 * t + (k + 1) % 3]));
            if (it != owner.end() && it->second == t)
                owner.erase(it);
        }
        tr[3 * t] = p0, tr[3 * t + 1] = p1, tr[3 * t + 2] = p2;
        owner[key(p0, p1)] = t, owner[key(p1, p2)] = t, owner[key(p2, p0)] = t;
        if (!is_changed[t])
            is_changed[t] = 1, changed.push_back(t);
    };
    const auto orient = [&](std::uint32_t p, std::uint32_t r, std::uint32_t s) {
        const Vertex &a0 = a.vertices[p], &b0 = a.vertices[r], &c0 = a.vertices[s];
        return std::int64_t(b0.u - a0.u) * (c0.v - a0.v) -
               std::int64_t(b0.v - a0.v) * (c0.u - a0.u);
    };
    // Whether s lies strictly inside the circle through p, r, t (counter-clockwise).
    const auto incircle = [&](std::uint32_t p, std::uint32_t r, std::uint32_t t, std::uint32_t s) {
        const Vertex &d = a.vertices[s];
        const auto lift = [&](std::uint32_t k) {
            const Wide x = a.vertices[k].u - d.u, y = a.vertices[k].v - d.v;
            return std::array<Wide, 3>{x, y, x * x + y * y};
        };
        const auto pa = lift(p), pb = lift(r), pc = lift(t);
        const Wide det = pa[2] * (pb[0] * pc[1] - pc[0] * pb[1]) +
                         pb[2] * (pc[0] * pa[1] - pa[0] * pc[1]) +
                         pc[2] * (pa[0] * pb[1] - pb[0] * pa[1]);
        return det > 0;
    };
    const auto third = [&](std::uint32_t t, std::uint32_t p, std::uint32_t r) {
        for (std::size_t k = 0; k < 3; ++k)
            if (tr[3 * t + k] != p && tr[3 * t + k] != r)
                return tr[3 * t + k];
        return p;
    };
    // Makes vertex n (the last) a vertex of the triangulation at its place, from triangle t:
    // the triangle that holds it splits in three, or the two on the edge it lies on in two each,
    // then Lawson's flips round it. Returns false (and leaves the mesh as it was) when it lies on
    // a vertex, `at`, or the walk from t does not reach it.
    const auto place = [&](std::uint32_t n, std::uint32_t t, std::uint32_t &at) {
        std::array<std::int64_t, 3> o{};
        std::array<std::uint32_t, 3> c{};
        bool found = false;
        for (int walk = 0; walk < 64 && !found; ++walk) {
            c = {tr[3 * t], tr[3 * t + 1], tr[3 * t + 2]};
            if (orient(c[0], c[1], c[2]) <= 0)
                break;
            o = {orient(c[0], c[1], n), orient(c[1], c[2], n), orient(c[2], c[0], n)};
            std::size_t k = 0;
            while (k < 3 && o[k] >= 0)
                ++k;
            found = k == 3;
            if (found)
                break;
            const auto it = owner.find(key(c[(k + 1) % 3], c[k]));
            if (it == owner.end())
                break;
            t = it->second;
        }
        const int zeros = int(o[0] == 0) + int(o[1] == 0) + int(o[2] == 0);
        if (!found || zeros > 1) {
            for (const std::uint32_t k : c)
                if (found && a.vertices[k].u == a.vertices[n].u &&
                    a.vertices[k].v == a.vertices[n].v)
                    at = k;
            return false;
        }
        // The edges round the new vertex, each (x, y) of a triangle (x, y, n).
        std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
        if (zeros == 0) {
            const std::uint32_t t1 = std::uint32_t(tr.size() / 3);
            set(t, c[0], c[1], n), set(t1, c[1], c[2], n), set(t1 + 1, c[2], c[0], n);
            edges = {{c[0], c[1]}, {c[1], c[2]}, {c[2], c[0]}};
        } else {
            // On edge (c[0], c[1]) after turning the triangle: split it and the one across.
            while (o[0] != 0) {
                std::rotate(c.begin(), c.begin() + 1, c.end());
                std::rotate(o.begin(), o.begin() + 1, o.end());
            }
            const auto it = owner.find(key(c[1], c[0]));
            if (it == owner.end())
                return false;
            const std::uint32_t u = it->second, d = third(u, c[0], c[1]);
            const std::uint32_t t1 = std::uint32_t(tr.size() / 3);
            set(t, c[2], c[0], n), set(u, c[0], d, n), set(t1, c[1], c[2], n),
                set(t1 + 1, d, c[1], n);
            edges = {{c[2], c[0]}, {c[0], d}, {c[1], c[2]}, {d, c[1]}};
        }
        while (!edges.empty()) {
            const auto [x, y] = edges.back();
            edges.pop_back();
            const auto mine = owner.find(key(x, y)), other = owner.find(key(y, x));
            if (mine == owner.end() || other == owner.end())
                continue;
            const std::uint32_t s1 = mine->second, s2 = other->second, f = third(s2, x, y);
            if (!incircle(x, y, n, f) || orient(x, f, n) <= 0 || orient(f, y, n) <= 0)
                continue;
            set(s1, x, f, n), set(s2, f, y, n);
            edges.push_back({x, f}), edges.push_back({f, y});
        }
        return true;
    };
    // Makes post (i, j), under triangle `own`, a vertex: at its rounded place; or, when that is
    // a vertex of the triangle next to its own, by flipping the edge between them (over a convex
    // quadrilateral) so that its triangle has that vertex; or at another corner of the u/v cell
    // round the post, the nearest free one.
    const GeoRect rect = tile_rect(id);
    const auto insert = [&](std::int64_t i, std::int64_t j, const std::uint32_t own) {
        const double pu = offset_units(g.lon0, g.dlon, i, rect.west, id.z),
                     pv = offset_units(g.lat0, g.dlat, j, rect.south, id.z);
        std::array<std::array<int, 2>, 4> cell;
        for (int k = 0; k < 4; ++k)
            cell[std::size_t(k)] = {int(std::floor(pu)) + (k & 1), int(std::floor(pv)) + (k >> 1)};
        std::stable_sort(cell.begin(), cell.end(), [&](const auto &p, const auto &r) {
            return std::hypot(p[0] - pu, p[1] - pv) < std::hypot(r[0] - pu, r[1] - pv);
        });
        const std::uint32_t n = std::uint32_t(a.vertices.size());
        const double h = std::floor(double(g.at(i, j)) / q.step + 0.5) * q.step;
        for (std::size_t k = 0; k < cell.size(); ++k) {
            const auto [u, v] = cell[k];
            if (u < 1 || v < 1 || u >= k_quantized_max || v >= k_quantized_max)
                continue;
            a.vertices.push_back({u, v, h});
            std::uint32_t at = n;
            if (place(n, own, at)) {
                q.codes.push_back(q.code(h));
                return true;
            }
            a.vertices.pop_back();
            if (k > 0 || at == n)
                continue;
            for (std::size_t e = 0; e < 3; ++e) {
                const std::uint32_t x = tr[3 * own + e], y = tr[3 * own + (e + 1) % 3],
                                    w = tr[3 * own + (e + 2) % 3];
                const auto it = owner.find(key(y, x));
                if (it == owner.end() || third(it->second, x, y) != at || orient(x, at, w) <= 0 ||
                    orient(at, y, w) <= 0)
                    continue;
                const std::uint32_t across = it->second;
                set(own, x, at, w), set(across, at, y, w);
                return true;
            }
        }
        return false;
    };
    std::size_t made = 0;
    for (int rounds = 0; rounds < k_max_rounds; ++rounds) {
        std::vector<std::pair<double, std::uint32_t>> over;
        for (std::uint32_t t = 0; t < errors.size(); ++t)
            if (errors[t].over > 0.0)
                over.emplace_back(errors[t].over, t);
        std::sort(over.begin(), over.end(), [](const auto &p, const auto &r) {
            return p.first > r.first || (p.first == r.first && p.second < r.second);
        });
        for (const std::uint32_t t : changed)
            is_changed[t] = 0;
        changed.clear();
        std::size_t round = 0;
        for (const auto &[worst, t] : over) {
            if (is_changed[t] || made + round >= k_max_repairs)
                continue;
            round += insert(errors[t].i, errors[t].j, t) ? 1 : 0;
        }
        if (round == 0)
            break;
        made += round;
        const Measure again = measure(g, id, a.vertices, q, tr, changed, bound, errors);
        m.max_error = again.max_error, m.max_drawn = again.max_drawn;
    }
    m.inserted = std::int64_t(made);
    return m;
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
