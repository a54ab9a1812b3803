// Greedy insertion into a Delaunay TIN on a DEM's lattice (greedy.hpp).
//
// Triangles live in slots of three half-edges: half-edge 3t + k runs from corner k of triangle t
// to corner k + 1, counter-clockwise in lattice coordinates (column, row), which are the world's
// (east, north) scaled; twin[e] is the half-edge running the other way (-1 on the outline). An
// insertion re-uses the slots of the triangles it replaces, so a slot is never freed. Every new or
// changed triangle is scanned once for its farthest sample (its candidate) before the next
// insertion, and a queue of the triangles whose candidate is too far picks the next sample.
#include "tinlod/greedy.hpp"

#include "lattice_triangle.hpp"
#include "triangle_plane.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace tinlod {

namespace {

__extension__ typedef __int128 Int128;

// An entry of the queue of triangles to refine: a triangle is queued again whenever it changes,
// and an entry whose version is no longer its triangle's is dropped when it comes to the top.
struct Queued {
    std::int32_t triangle;
    std::uint32_t version;
};

// The queue orders triangles by their farthest sample's distance in buckets of a fraction of an
// octave (GreedyOptions::buckets_per_octave; half by default), last in first out within a bucket,
// not exactly: a heap's pops miss the cache, a bucket's last entries are the triangles just made,
// near each other (docs/decisions/002-greedy-insertion.md).
constexpr int k_buckets = 2048;

struct Inserter {
    const Heightfield &hf;
    std::int64_t w;
    double threshold;                  // a triangle is queued when its farthest sample is farther
    double slope_margin;               // GreedyOptions::slope_margin
    double buckets_per_octave;         // GreedyOptions::buckets_per_octave
    bool exact64;                      // in_circle fits in 64 bits (lattice side <= 16385)
    std::vector<std::uint32_t> points; // sample id per node
    std::vector<std::int32_t> px, py;  // lattice column and row per node
    std::vector<std::int32_t> corner;  // node per half-edge: the half-edge's start
    std::vector<std::int32_t> twin;
    std::vector<std::uint32_t> candidate;     // per triangle: its farthest sample
    std::vector<std::uint32_t> version;       // per triangle: bumped when its slot is rewritten
    std::vector<std::uint8_t> is_pending;     // per triangle: waiting for its scan
    std::vector<std::vector<Queued>> buckets; // by distance over the threshold
    int top_bucket = -1;                      // no bucket above holds an entry
    std::vector<std::int32_t> pending;        // triangles to scan

    Inserter(const Heightfield &h, const GreedyOptions &o)
        : hf(h), w(h.width), threshold(o.max_error), slope_margin(o.slope_margin),
          buckets_per_octave(std::max(1, o.buckets_per_octave)),
          exact64(std::max(h.width, h.height) <= 16385), buckets(k_buckets) {}

    // Twice the signed area of (a, b, p) in lattice coordinates: > 0 when p is left of a -> b.
    std::int64_t orient(std::int32_t a, std::int32_t b, std::int32_t p) const {
        return std::int64_t(px[b] - px[a]) * (py[p] - py[a]) -
               std::int64_t(py[b] - py[a]) * (px[p] - px[a]);
    }

    // Whether node d lies strictly inside the circumcircle of the counter-clockwise triangle abc,
    // exactly: with coordinate differences up to 2^14 the terms stay under 2^60, beyond that
    // they need 128 bits (2^67 on a 65536-wide lattice).
    template <class Int>
    bool in_circle_as(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) const {
        const Int ax = px[a] - px[d], ay = py[a] - py[d];
        const Int bx = px[b] - px[d], by = py[b] - py[d];
        const Int cx = px[c] - px[d], cy = py[c] - py[d];
        const Int a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
        return ax * (by * c2 - b2 * cy) - ay * (bx * c2 - b2 * cx) + a2 * (bx * cy - by * cx) > 0;
    }
    bool in_circle(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) const {
        return exact64 ? in_circle_as<std::int64_t>(a, b, c, d) : in_circle_as<Int128>(a, b, c, d);
    }

    std::int32_t add_point(std::uint32_t sample) {
        points.push_back(sample);
        px.push_back(std::int32_t(sample % std::uint32_t(w)));
        py.push_back(std::int32_t(sample / std::uint32_t(w)));
        return std::int32_t(points.size() - 1);
    }

    // Writes triangle (a, b, c) with outer twins ab, bc, ca into slot e / 3 (a new slot when e < 0)
    // and links the twins back; returns its first half-edge. The slot's queued entry goes stale.
    std::int32_t set_triangle(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t ab,
                              std::int32_t bc, std::int32_t ca, std::int32_t e = -1) {
        if (e < 0) {
            e = std::int32_t(corner.size());
            corner.resize(corner.size() + 3);
            twin.resize(twin.size() + 3);
            candidate.push_back(0);
            version.push_back(0);
            is_pending.push_back(0);
        }
        const std::int32_t t = e / 3;
        corner[e] = a;
        corner[e + 1] = b;
        corner[e + 2] = c;
        const std::int32_t outer[3] = {ab, bc, ca};
        for (int k = 0; k < 3; ++k) {
            twin[e + k] = outer[k];
            if (outer[k] >= 0)
                twin[outer[k]] = e + k;
        }
        ++version[t];
        if (!is_pending[t]) {
            is_pending[t] = 1;
            pending.push_back(t);
        }
        return e;
    }

    // The next triangle to refine, taken from the queue (false: none is left).
    bool pop(std::int32_t &t) {
        for (; top_bucket >= 0; --top_bucket) {
            std::vector<Queued> &bucket = buckets[std::size_t(top_bucket)];
            while (!bucket.empty()) {
                const Queued q = bucket.back();
                bucket.pop_back();
                if (version[q.triangle] == q.version) {
                    t = q.triangle;
                    return true;
                }
            }
        }
        return false;
    }

    // ---- Scans ----

    // scan's samples of the triangle with corner samples sa, sb, sc, a row span at a time.
    void scan_rows(std::uint32_t sa, std::uint32_t sb, std::uint32_t sc,
                   const TrianglePlane::Rows &plane, double &worst, std::uint32_t &at) const {
        const LatticeTriangle tri(std::uint32_t(w), sa, sb, sc);
        for (std::int64_t r = tri.first_row; r <= tri.last_row; ++r) {
            const auto [lo, hi] = tri.span(r);
            const float *row = hf.z.data() + r * w;
            const double base = plane.start(double(r));
            const auto dev = [&](std::int64_t c) {
                return plane.deviation(base, double(c), double(row[c]));
            };
            // The row's largest deviation in four independent chains, then its place only when it
            // beats the triangle's so far.
            double m0 = 0.0, m1 = 0.0, m2 = 0.0, m3 = 0.0;
            std::int64_t c = lo;
            for (; c + 3 <= hi; c += 4) {
                m0 = std::max(m0, dev(c));
                m1 = std::max(m1, dev(c + 1));
                m2 = std::max(m2, dev(c + 2));
                m3 = std::max(m3, dev(c + 3));
            }
            for (; c <= hi; ++c)
                m0 = std::max(m0, dev(c));
            const double row_max = std::max(std::max(m0, m1), std::max(m2, m3));
            if (row_max > worst) {
                worst = row_max;
                for (c = lo; c < hi && dev(c) != row_max; ++c) {
                }
                at = std::uint32_t(r * w + c);
            }
        }
    }

    // Finds triangle t's farthest sample (corners excluded) and queues t when it lies farther than
    // the threshold. The samples are those of the closed triangle, in row order; the first of the
    // farthest is the candidate.
    void scan(std::int32_t t) {
        const std::int32_t na = corner[3 * t], nb = corner[3 * t + 1], nc = corner[3 * t + 2];
        const std::uint32_t sa = points[na], sb = points[nb], sc = points[nc];
        const TrianglePlane::Rows plane = TrianglePlane::rows(
            {px[na], py[na], hf.z[sa]}, {px[nb], py[nb], hf.z[sb]}, {px[nc], py[nc], hf.z[sc]});
        double worst = 0.0;
        std::uint32_t at = sa;
        const std::int64_t x[3] = {px[na], px[nb], px[nc]}, y[3] = {py[na], py[nb], py[nc]};
        if (box_samples(x, y) <= k_small_box)
            visit_box(x, y, [&](std::int64_t c, std::int64_t r) {
                const double d = plane.deviation(plane.start(double(r)), double(c),
                                                 double(hf.z[std::size_t(r * w + c)]));
                if (d > worst) {
                    worst = d;
                    at = std::uint32_t(r * w + c);
                }
                return true;
            });
        else
            scan_rows(sa, sb, sc, plane, worst, at);
        candidate[t] = at;
        is_pending[t] = 0;
        if (slope_margin > 0.0)
            worst += slope_margin * std::sqrt(plane.gx * plane.gx / (hf.dx * hf.dx) +
                                              plane.gy * plane.gy / (hf.dy * hf.dy));
        if (worst > threshold && at != sa && at != sb && at != sc) {
            const int b = int(
                std::min(double(k_buckets - 1), std::log2(worst / threshold) * buckets_per_octave));
            buckets[std::size_t(b)].push_back({t, version[t]});
            top_bucket = std::max(top_bucket, b);
        }
    }

    void flush() {
        for (const std::int32_t t : pending)
            scan(t);
        pending.clear();
    }

    // ---- Insertion ----

    // Restores the Delaunay condition across half-edge a, whose triangle's third corner is the
    // node just inserted, flipping and recursing outward.
    void legalize(std::int32_t a) {
        const std::int32_t b = twin[a];
        if (b < 0)
            return;
        const std::int32_t a0 = a - a % 3, b0 = b - b % 3;
        const std::int32_t al = a0 + (a + 1) % 3, ar = a0 + (a + 2) % 3;
        const std::int32_t bl = b0 + (b + 2) % 3, br = b0 + (b + 1) % 3;
        const std::int32_t p0 = corner[ar], pr = corner[a], pl = corner[al], p1 = corner[bl];
        if (!in_circle(pr, pl, p0, p1))
            return;
        const std::int32_t hal = twin[al], har = twin[ar], hbl = twin[bl], hbr = twin[br];
        const std::int32_t t0 = set_triangle(p0, p1, pl, -1, hbl, hal, a0);
        const std::int32_t t1 = set_triangle(p1, p0, pr, t0, har, hbr, b0);
        legalize(t0 + 1);
        legalize(t1 + 2);
    }

    // Inserts node n, which lies on half-edge a (inside the edge).
    void split_edge(std::int32_t n, std::int32_t a) {
        const std::int32_t a0 = a - a % 3;
        const std::int32_t al = a0 + (a + 1) % 3, ar = a0 + (a + 2) % 3;
        const std::int32_t p0 = corner[ar], pr = corner[a], pl = corner[al];
        const std::int32_t hal = twin[al], har = twin[ar];
        const std::int32_t b = twin[a];
        if (b < 0) {
            const std::int32_t t0 = set_triangle(n, p0, pr, -1, har, -1, a0);
            const std::int32_t t1 = set_triangle(p0, n, pl, t0, -1, hal);
            legalize(t0 + 1);
            legalize(t1 + 2);
            return;
        }
        const std::int32_t b0 = b - b % 3;
        const std::int32_t bl = b0 + (b + 2) % 3, br = b0 + (b + 1) % 3;
        const std::int32_t p1 = corner[bl], hbl = twin[bl], hbr = twin[br];
        const std::int32_t t0 = set_triangle(p0, pr, n, har, -1, -1, a0);
        const std::int32_t t1 = set_triangle(pr, p1, n, hbr, -1, t0 + 1, b0);
        const std::int32_t t2 = set_triangle(p1, pl, n, hbl, -1, t1 + 1);
        const std::int32_t t3 = set_triangle(pl, p0, n, hal, t0 + 2, t2 + 1);
        legalize(t0);
        legalize(t1);
        legalize(t2);
        legalize(t3);
    }

    // Inserts the candidate of triangle t.
    void step(std::int32_t t) {
        const std::int32_t e = 3 * t;
        const std::int32_t p0 = corner[e], p1 = corner[e + 1], p2 = corner[e + 2];
        const std::int32_t n = add_point(candidate[t]);
        if (orient(p0, p1, n) == 0)
            split_edge(n, e);
        else if (orient(p1, p2, n) == 0)
            split_edge(n, e + 1);
        else if (orient(p2, p0, n) == 0)
            split_edge(n, e + 2);
        else {
            const std::int32_t h0 = twin[e], h1 = twin[e + 1], h2 = twin[e + 2];
            const std::int32_t t0 = set_triangle(p0, p1, n, h0, -1, -1, e);
            const std::int32_t t1 = set_triangle(p1, p2, n, h1, -1, t0 + 1);
            const std::int32_t t2 = set_triangle(p2, p0, n, h2, t0 + 2, t1 + 1);
            legalize(t0);
            legalize(t1);
            legalize(t2);
        }
        flush();
    }
};

} // namespace

GreedyTin greedy_tin(const Heightfield &hf, const GreedyOptions &options) {
    if (hf.width < 2 || hf.height < 2)
        throw std::invalid_argument("greedy_tin: the DEM needs at least 2 x 2 samples");
    if (!(options.max_error > 0.0))
        throw std::invalid_argument("greedy_tin: max_error must be > 0");
    Inserter ins(hf, options);
    // The seed: a regular grid of nodes every seed_step samples (and on the last row and column),
    // each cell split along the same diagonal (Delaunay: a cell's four corners are cocircular).
    // Half-edges are counted in 32 bits: 6 per node (a TIN has about twice as many triangles as
    // nodes, and the outline's nodes fewer). A seed grid finer than that is thinned.
    constexpr std::int64_t k_max_nodes = (std::numeric_limits<std::int32_t>::max() - 64) / 6;
    int step = options.seed_step > 0 ? options.seed_step : std::max(hf.width, hf.height);
    const auto lines = [&](int samples) { return std::int64_t{(samples - 2) / step} + 2; };
    while (lines(hf.width) * lines(hf.height) > k_max_nodes)
        step *= 2;
    std::vector<std::uint32_t> xs, ys;
    for (int x = 0; x < hf.width - 1; x += step)
        xs.push_back(std::uint32_t(x));
    xs.push_back(std::uint32_t(hf.width - 1));
    for (int y = 0; y < hf.height - 1; y += step)
        ys.push_back(std::uint32_t(y));
    ys.push_back(std::uint32_t(hf.height - 1));
    const std::size_t nx = xs.size(), cells_x = nx - 1;
    for (const std::uint32_t y : ys)
        for (const std::uint32_t x : xs)
            ins.add_point(y * std::uint32_t(hf.width) + x);
    // Cell (i, j): triangles 2k (south-east half) and 2k + 1 (north-west half), k its index; each
    // links to the cell below and the one to the left, made before it.
    const auto node = [&](std::size_t x, std::size_t y) { return std::int32_t(y * nx + x); };
    const auto half_edge = [](std::size_t k, int side) { return std::int32_t(3 * k + side); };
    for (std::size_t j = 0; j + 1 < ys.size(); ++j)
        for (std::size_t i = 0; i < cells_x; ++i) {
            const std::int32_t below = j > 0 ? half_edge(2 * ((j - 1) * cells_x + i) + 1, 1) : -1;
            const std::int32_t left = i > 0 ? half_edge(2 * (j * cells_x + i - 1), 1) : -1;
            const std::int32_t se =
                ins.set_triangle(node(i, j), node(i + 1, j), node(i + 1, j + 1), below, -1, -1);
            ins.set_triangle(node(i, j), node(i + 1, j + 1), node(i, j + 1), se + 2, -1, left);
        }
    ins.flush();
    GreedyTin out;
    const std::int64_t max_nodes =
        options.max_nodes > 0 ? std::min(options.max_nodes, k_max_nodes) : k_max_nodes;
    const auto on_outline = [&](std::uint32_t sample) {
        const std::uint32_t c = sample % std::uint32_t(hf.width),
                            r = sample / std::uint32_t(hf.width);
        return c == 0 || r == 0 || c + 1 == std::uint32_t(hf.width) ||
               r + 1 == std::uint32_t(hf.height);
    };
    std::int32_t t;
    while (ins.pop(t)) {
        const std::int64_t triangles = std::int64_t(ins.corner.size() / 3);
        if (std::int64_t(ins.points.size()) >= max_nodes ||
            (options.max_triangles > 0 &&
             triangles + (on_outline(ins.candidate[std::size_t(t)]) ? 1 : 2) >
                 options.max_triangles)) {
            out.stopped = true;
            break;
        }
        ins.step(t);
    }
    Retrieval &r = out.tin;
    r.nodes = std::move(ins.points);
    r.z.reserve(r.nodes.size());
    for (const std::uint32_t s : r.nodes)
        r.z.push_back(hf.z[s]);
    r.triangles.reserve(ins.corner.size());
    for (const std::int32_t n : ins.corner)
        r.triangles.push_back(r.nodes[std::size_t(n)]);
    out.twin = std::move(ins.twin);
    return out;
}

} // namespace tinlod
