// The SP of an erase (erase_cost.hpp).
#include "erase/erase_cost.hpp"

#include "erase/lattice_scan.hpp"
#include "lattice_triangle.hpp"
#include "tinlod/significance.hpp"

#include <algorithm>

namespace tinlod::erase {

void new_weights(EraserState &s, bool keep) {
    s.weights.unit_weights = s.weights.model == SpModel::vertical;
    if (s.weights.unit_weights || !keep) {
        std::vector<float>().swap(s.weights.per_vertex);
        return;
    }
    s.weights.per_vertex.resize(s.input.nodes);
    for (std::uint32_t x = 0; x < s.input.nodes; ++x)
        s.weights.per_vertex[x] = float_up(s.weights.weigher(to_glm(node_point(s, x))));
}

void classify_nodes(EraserState &s) {
    const Mesh &m = *s.input.mesh;
    s.live.flags.resize(s.input.nodes);
    for (std::uint8_t &f : s.live.flags)
        f &= k_unread;
    if (s.live.node_keys)
        std::fill(s.live.slot_stamp.begin(), s.live.slot_stamp.end(), std::uint8_t(0));
    else
        s.live.stamp.assign(s.input.nodes, 0);
    s.live.pass = 0;
    for (auto v : m.vertices()) {
        const HH he = m.halfedge_handle(v);
        if (!he.is_valid() ||
            (m.is_boundary(he) && (!s.input.xy || !s.input.options.erase_boundary)))
            s.live.flags[node_of(s, v)] |= k_locked;
    }
    for (std::size_t x = 0; x < s.history.record_of.size(); ++x)
        if (s.history.record_of[x] == k_absent)
            s.live.flags[x] |= k_locked;
    s.weights.weigher =
        Weigher(Significance::of(s.weights.model, s.weights.view, s.weights.significance));
    new_weights(s, true);
}

bool raise_pending(const EraserState &s, Hole &h, double limit) {
    std::vector<Hole::Pending> &p = h.pending;
    for (Hole::Pending &q : p)
        if (q.upper > limit) {
            q.weighted = weighted(s, q.node, q.dev);
            if (q.weighted > limit) {
                h.sp = q.weighted;
                h.star = q.node;
                h.star_dev = q.dev;
                p.clear();
                return false;
            }
        }
    std::vector<std::uint32_t> &order = h.pending_order;
    order.resize(p.size());
    for (std::uint32_t i = 0; i < std::uint32_t(p.size()); ++i)
        order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return p[a].upper > p[b].upper; });
    double best = h.sp;
    std::int64_t best_at = -1; // -1: the SP before the band
    for (const std::uint32_t i : order) {
        Hole::Pending &q = p[i];
        if (q.upper < best)
            break; // nor any after it: its weighted deviation is at most its bound
        if (q.weighted < 0.0)
            q.weighted = weighted(s, q.node, q.dev);
        if (q.weighted > best || (q.weighted == best && best_at > std::int64_t(i))) {
            best = q.weighted;
            best_at = i;
        }
    }
    if (best_at >= 0) {
        h.sp = best;
        h.star = p[std::size_t(best_at)].node;
        h.star_dev = p[std::size_t(best_at)].dev;
    }
    p.clear();
    return true;
}

// The min-max hole's triangles whose costs scanned all their samples (min_max_hole): per triangle
// its largest deviation and the first sample in row order that has it (-1 when none deviates), the
// plane, margin and order scan_hole's scan has, so the hole's measure takes them over instead of
// scanning those triangles again (docs/decisions/044-erase-evaluations.md).
struct ScannedTriangles {
    struct Scan {
        std::uint8_t a, b, c;
        double most;
        std::int32_t worst;
    };
    std::array<Scan, 128> list; // the first ones; a triangle past them is scanned again
    int count = 0;
    void add(int a, int b, int c, double most, std::int32_t worst) {
        if (count < int(list.size()))
            list[std::size_t(count++)] = {std::uint8_t(a), std::uint8_t(b), std::uint8_t(c), most,
                                          worst};
    }
    const Scan *find(const RingTriangle &t) const {
        for (int i = 0; i < count; ++i)
            if (list[std::size_t(i)].a == t.a && list[std::size_t(i)].b == t.b &&
                list[std::size_t(i)].c == t.c)
                return &list[std::size_t(i)];
        return nullptr;
    }
};

// evaluate's walk over the nodes a grid TIN's hole swallows (v at pv among them): each new
// triangle's samples, with their largest deviation and worst sample kept for retriangulate. A
// sample whose deviation times the largest weight in its band's box (within the old fan's largest
// deviation of its corners' heights) could raise the SP waits for the band's end
// (raise_pending), which weighs few of them: raised one by one in scan order, each raise made the
// next sample's weight look worth computing. A sample whose bound exceeds `limit` settles the
// band's samples so far at once, so a failing evaluation stops where it did
// (docs/decisions/011-deferred-weighing.md). Stops once the SP exceeds `limit`; sets h.deferred
// instead when the hole holds more than `max_swallowed` samples. A triangle `known` holds (unit
// weights, its samples within `limit`) is taken from it: the SP rises to its worst sample as the
// scan's raises would, the first of the largest in scan order.
static void scan_hole(const EraserState &s, Hole &h, const glm::dvec3 &pv, double limit,
                      std::size_t max_swallowed, const ScannedTriangles *known) {
    if (std::size_t(lattice_inside(s, h)) > max_swallowed) {
        h.deferred = true;
        return;
    }
    const Mesh &m = *s.input.mesh;
    float fan_dev = 0.0f;
    double zlo = pv.z, zhi = pv.z;
    for (int i = 0; i < h.n; ++i) {
        zlo = std::min(zlo, h.p[i].z);
        zhi = std::max(zhi, h.p[i].z);
        const FH f = m.face_handle(h.h[i]);
        if (f.is_valid())
            fan_dev = std::max(fan_dev, s.faces.face_maxdev[f.idx()]);
    }
    const double dz = 1.001 * double(fan_dev);
    const auto band = [&](const glm::dvec2 &lo, const glm::dvec2 &hi) {
        return s.weights.unit_weights
                   ? 1.0
                   : s.weights.weigher.bound({lo, zlo - dz}, {hi, zhi + dz}) * k_rounded_weight;
    };
    for (int t = 0; t < h.ntri; ++t) {
        const ScannedTriangles::Scan *scan =
            known && s.weights.unit_weights ? known->find(h.tri[t]) : nullptr;
        if (scan && !(scan->most > limit)) {
            h.tri_maxdev[t] = float_up(scan->most);
            h.tri_worst[t] = scan->worst;
            if (scan->most > h.sp) {
                h.sp = scan->most;
                h.star = std::uint32_t(scan->worst);
                h.star_dev = scan->most;
            }
            continue;
        }
        const TrianglePlane plane = h.frame[t].plane; // a copy: the scan's stores cannot move it
        const double margin = plane.margin_over(h.p[h.tri[t].a], h.p[h.tri[t].b], h.p[h.tri[t].c]);
        double maxdev = 0.0;
        std::int32_t worst = -1;
        const bool whole = scan_lattice(
            s, node_of(s, h.r[h.tri[t].a]), node_of(s, h.r[h.tri[t].b]),
            node_of(s, h.r[h.tri[t].c]), band,
            [&](std::uint32_t u, const Mesh::Point &p, double bound) {
                const double dev = plane.deviation(p[0], p[1], p[2], margin);
                if (dev > maxdev) {
                    maxdev = dev;
                    worst = std::int32_t(u);
                }
                const double upper = dev * bound;
                if (!(upper > h.sp))
                    return true;
                h.pending.push_back({u, dev, upper, -1.0});
                return !(upper > limit) || raise_pending(s, h, limit);
            },
            [&] { return raise_pending(s, h, limit); });
        h.tri_maxdev[t] = float_up(maxdev);
        h.tri_worst[t] = worst;
        if (!whole)
            return;
    }
}

// Whether evaluate tries the hole's min-max triangulation when the ears' exceeds the limit: a
// vertical bound on a grid TIN without a budget (simplify --max-error), where a node the Delaunay
// ears keep may still go under triangles that follow the terrain
// (docs/decisions/023-fine-bounds.md). Others keep the ears alone.
static bool data_dependent(const EraserState &s) {
    return s.input.xy && s.input.grid_w > 0 && s.weights.unit_weights &&
           s.input.options.max_nodes <= 0 && !s.input.history.shallow_history;
}

// Whether a sample deviates more than `limit` (vertically) from every triangle over three ring
// nodes (counter-clockwise, its closed lattice triangle holding the sample); a lower bound of the
// least of those deviations in `least` (infinite when none holds the sample). Every triangle a
// triangulation of the hole may use is among these, and a hair over the limit still counts as
// within: the heights here, from the sample's exact lattice areas, round otherwise than the erase's
// planes, and the rounding never rules a triangulation out. When
// the erased node or the ears' worst sample is over the limit under all of them, no triangulation
// holds the bound: most failing evaluations end here, before the ears' samples are scanned or the
// min-max hole's triangles (docs/decisions/024-simplify-speed.md).
static bool over_every_triangle(const EraserState &s, const Hole &h, std::uint32_t sample,
                                double limit, double &least) {
    const std::int64_t w = s.input.grid_w, xs = sample % w, ys = sample / w;
    const glm::dvec3 p = to_glm(node_point(s, sample));
    // The hair: far under the erase's own (its limit sits 1e-6 under the bound, where quantised
    // heights put many deviations exactly at the bound), far over the heights' rounding.
    const double stop = limit * (1.0 + 1e-9) + 1e-12 * std::abs(p.z);
    least = INFINITY;
    // side[a][b] (a < b): twice the signed area of (ring node a, ring node b, the sample), lattice
    // units; side[b][a] is its negation.
    std::array<std::int64_t, k_max_ring> rx, ry;
    std::array<std::array<std::int64_t, k_max_ring>, k_max_ring> side;
    for (int i = 0; i < h.n; ++i) {
        const std::int64_t u = node_of(s, h.r[i]);
        rx[std::size_t(i)] = u % w - xs;
        ry[std::size_t(i)] = u / w - ys;
    }
    for (int a = 0; a < h.n; ++a)
        for (int b = a + 1; b < h.n; ++b)
            side[std::size_t(a)][std::size_t(b)] = rx[a] * ry[b] - ry[a] * rx[b];
    for (int a = 0; a < h.n; ++a)
        for (int b = a + 1; b < h.n; ++b) {
            const std::int64_t s0 = side[std::size_t(a)][std::size_t(b)];
            const double high = std::max(h.p[a].z, h.p[b].z), low = std::min(h.p[a].z, h.p[b].z);
            for (int c = b + 1; c < h.n; ++c) {
                const std::int64_t s1 = side[std::size_t(b)][std::size_t(c)],
                                   s2 = -side[std::size_t(a)][std::size_t(c)];
                if (!((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)))
                    continue;
                if (!(orient(h.q[a], h.q[b], h.q[c]) > 0.0))
                    continue;
                // The plane at the sample lies between the corners' heights.
                const double below = p.z - std::max(high, h.p[c].z),
                             above = std::min(low, h.p[c].z) - p.z;
                if (below > stop || above > stop) {
                    least = std::min(least, std::max(below, above));
                    continue;
                }
                // The plane's height at the sample from its exact barycentric weights (lattice
                // areas): within a few ulp of the plane the erase computes.
                const double z =
                    (h.p[a].z * double(s1) + h.p[b].z * double(s2) + h.p[c].z * double(s0)) /
                    double(s0 + s1 + s2);
                least = std::min(least, std::abs(p.z - z));
                if (least <= stop)
                    return false;
            }
        }
    return true;
}

// Whether the erase of the node in h cannot hold `limit` under any triangulation of its hole, on a
// grid TIN at a vertical bound (data_dependent): the node deviates more under every ring triangle
// that covers it (over_every_triangle). Then h's SP is a lower bound of the erase's cost, found
// before the ears are clipped (a ring the ears cannot clip is not erased either way).
static bool beyond_any_triangulation(const EraserState &s, Hole &h, double limit) {
    double least = 0.0;
    if (!data_dependent(s) || !over_every_triangle(s, h, node_of(s, h.v), limit, least))
        return false;
    h.sp = h.delta = h.star_dev = least;
    h.star = node_of(s, h.v);
    return true;
}

// The hole's triangulation whose largest sample deviation is least (min_max_triangulation, each
// triangle's samples scanned from the lattice), into h.tri when it keeps within `limit`; false
// when none does. The samples that put a triangle over its stop (the ears' worst first) are tried
// first on the next ones: the triangles overlap, and most fail on the same few samples. When the
// ears' worst sample is the erased node itself, beyond_any_triangulation has already found a ring
// triangle that holds it (most holes here: 87 % on dem_srtm30 at 5 m), so the cover test is asked
// of other samples only (docs/decisions/044-erase-evaluations.md).
static bool min_max_hole(const EraserState &s, Hole &h, double limit, ScannedTriangles &scanned) {
    double least = 0.0;
    if (h.star_dev > limit && h.star != node_of(s, h.v) &&
        over_every_triangle(s, h, h.star, limit, least))
        return false;
    std::array<RingTriangle, k_max_ring> tri;
    std::array<glm::dvec3, 8> witness;
    int witnesses = 0, next = 0;
    const auto add_witness = [&](std::uint32_t u) {
        witness[std::size_t(next)] = to_glm(node_point(s, u));
        next = (next + 1) % int(witness.size());
        witnesses = std::min(witnesses + 1, int(witness.size()));
    };
    if (h.star_dev > limit)
        add_witness(h.star);
    const std::int64_t w = s.input.grid_w;
    const Samples lattice = samples(s.input);
    std::array<std::int64_t, k_max_ring> rx, ry; // the ring's lattice columns and rows
    for (int i = 0; i < h.n; ++i) {
        rx[std::size_t(i)] = std::int64_t(node_of(s, h.r[i])) % w;
        ry[std::size_t(i)] = std::int64_t(node_of(s, h.r[i])) / w;
    }
    const auto cost = [&](int a, int b, int c, double stop) {
        const TrianglePlane plane =
            triangle_frame(h.q[a], h.q[b], h.q[c], true, h.p[a].z, h.p[b].z, h.p[c].z).plane;
        const double margin = plane.margin_over(h.p[a], h.p[b], h.p[c]);
        const auto deviation = [&](const Mesh::Point &p) {
            return plane.deviation(double(p[0]), double(p[1]), double(p[2]), margin);
        };
        for (int k = 0; k < witnesses; ++k) {
            const glm::dvec3 &w = witness[std::size_t(k)];
            const glm::dvec2 x(w.x, w.y);
            if (orient(h.q[a], h.q[b], x) > 0.0 && orient(h.q[b], h.q[c], x) > 0.0 &&
                orient(h.q[c], h.q[a], x) > 0.0) {
                const double d = deviation(Mesh::Point(w.x, w.y, w.z));
                if (d > stop)
                    return d; // strictly inside: a sample the scan visits
            }
        }
        // The triangle's samples but its corners, in row order: the first over `stop` ends the
        // scan.
        double most = 0.0;
        std::int32_t worst = -1;
        const std::int64_t x[3] = {rx[a], rx[b], rx[c]}, y[3] = {ry[a], ry[b], ry[c]};
        const bool whole = visit_inside(x, y, [&](std::int64_t col, std::int64_t row) {
            const double d = deviation(lattice.at(col, row));
            if (!(d > most))
                return true;
            most = d;
            worst = std::int32_t(row * w + col);
            if (!(most > stop))
                return true;
            add_witness(std::uint32_t(worst));
            return false;
        });
        if (whole)
            scanned.add(a, b, c, most, worst);
        return most;
    };
    const int count = min_max_triangulation(h.q.data(), h.n, limit, cost, tri.data());
    if (count != h.n - 2)
        return false;
    std::copy_n(tri.begin(), count, h.tri.begin());
    return true;
}

static void measure_hole(EraserState &s, VH v, const glm::dvec3 &pv, double limit,
                         std::size_t max_swallowed, const ScannedTriangles *known = nullptr);

// Whether evaluate tries the fans of the hole when the ears' triangulation exceeds the limit
// (EraseOptions::hole_fans): a one-off erase of a grid TIN at a screen bound without a budget. The
// Delaunay ears follow xy alone; a fan from a ring node (a half-edge collapse's triangulation) may
// follow the terrain (docs/decisions/033-node-erase-vs-collapses.md). A vertical bound has its
// min-max hole instead; a budget's keys are the ears' costs (its evaluations have no limit).
static bool fans_tried(const EraserState &s) {
    return s.input.options.hole_fans && s.input.xy && s.input.grid_w > 0 &&
           !s.weights.unit_weights && s.input.options.max_nodes <= 0 &&
           !s.input.history.shallow_history && s.follower == nullptr;
}

// Measures the fans of the interior hole in h (from each ring node in turn, those whose triangles
// all turn counter-clockwise) and stops at the first within `limit`, left in h; false when none is.
static bool first_fan_within(EraserState &s, VH v, const glm::dvec3 &pv, double limit,
                             std::size_t max_swallowed) {
    Hole &h = s.scratch.hole;
    const int n = h.n;
    for (int i = 0; i < n; ++i) {
        bool turns_left = true;
        for (int k = 1; k <= n - 2 && turns_left; ++k) {
            const int b = (i + k) % n, c = (i + k + 1) % n;
            turns_left = orient(h.q[i], h.q[b], h.q[c]) > 0.0;
            h.tri[std::size_t(k - 1)] = {std::uint8_t(i), std::uint8_t(b), std::uint8_t(c)};
        }
        if (!turns_left)
            continue;
        h.ntri = n - 2;
        frame_triangles(h, true);
        measure_hole(s, v, pv, limit, max_swallowed);
        if (!h.deferred && h.sp <= limit)
            return true;
    }
    return false;
}

bool evaluate(EraserState &s, VH v, double limit, std::size_t max_swallowed) {
    ++s.counters.evaluations;
    Hole &h = s.scratch.hole;
    h.deferred = false;
    const Mesh &m = *s.input.mesh;
    if (!gather_ring(m, v, h, s.input.options.max_valence))
        return false;
    const int n = h.n;
    const glm::dvec3 pv = to_glm(m.point(v));
    for (int i = 0; i < n; ++i)
        h.p[i] = to_glm(m.point(h.r[i]));
    const int fans = h.boundary ? n - 1 : n;
    if (s.input.xy) {
        h.origin = glm::dvec3(0.0);
        h.ex = {1, 0, 0};
        h.ey = {0, 1, 0};
        for (int i = 0; i < n; ++i)
            h.q[i] = {h.p[i].x, h.p[i].y};
        if (h.boundary) {
            const glm::dvec2 c(pv.x, pv.y);
            if (orient(h.q[0], c, h.q[n - 1]) != 0.0 || glm::dot(h.q[0] - c, h.q[n - 1] - c) >= 0.0)
                return false; // erasing it would move the outline
        }
    } else {
        glm::dvec3 normal(0.0);
        for (int i = 0; i < fans; ++i)
            normal += glm::cross(h.p[i] - pv, h.p[(i + 1) % n] - pv);
        const double len = glm::length(normal);
        if (!(len > 0.0))
            return false;
        const glm::dvec3 ez = normal / len;
        const glm::dvec3 helper = std::abs(ez.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        h.origin = pv;
        h.ex = glm::normalize(glm::cross(helper, ez));
        h.ey = glm::cross(ez, h.ex);
        for (int i = 0; i < n; ++i)
            h.q[i] = project(h, h.p[i]);
        for (int i = 0; i < fans; ++i)
            if (orient(glm::dvec2(0.0), h.q[i], h.q[(i + 1) % n]) <= 0.0)
                return false; // the fan is not star-shaped in its mean plane
    }
    if (beyond_any_triangulation(s, h, limit))
        return true;
    h.ntri = clip_ears(h.q.data(), n, h.tri.data());
    if (h.ntri != n - 2)
        return false;
    frame_triangles(h, s.input.xy);
    if (!s.input.xy)
        for (int t = 0; t < h.ntri; ++t) {
            const std::uint8_t c[3] = {h.tri[t].a, h.tri[t].b, h.tri[t].c};
            for (int k = 0; k < 3; ++k) {
                const int a = c[k], b = c[(k + 1) % 3];
                if (b == (a + 1) % n)
                    continue; // a ring edge
                if (find_halfedge(m, h.r[a], h.r[b]).is_valid())
                    return false; // the diagonal exists outside the hole: non-manifold
            }
        }
    measure_hole(s, v, pv, limit, max_swallowed);
    ScannedTriangles scanned;
    if (h.sp > limit && !h.deferred && n > 3 && data_dependent(s) &&
        min_max_hole(s, h, limit, scanned)) {
        frame_triangles(h, s.input.xy);
        measure_hole(s, v, pv, limit, max_swallowed, &scanned);
    } else if (h.sp > limit && !h.deferred && n > 3 && !h.boundary && fans_tried(s)) {
        const std::array<RingTriangle, k_max_ring> ears = h.tri;
        if (!first_fan_within(s, v, pv, limit, max_swallowed)) {
            // The ears' cost stays the node's key, as without the fans.
            h.tri = ears;
            h.ntri = n - 2;
            frame_triangles(h, true);
            measure_hole(s, v, pv, limit, max_swallowed);
        }
    }
    return true;
}

// evaluate's SP of the hole's triangulation h.tri (framed): every node the new triangles swallow,
// and on a grid TIN every sample, until the SP exceeds `limit` (see scan_hole).
static void measure_hole(EraserState &s, VH v, const glm::dvec3 &pv, double limit,
                         std::size_t max_swallowed, const ScannedTriangles *known) {
    Hole &h = s.scratch.hole;
    const Mesh &m = *s.input.mesh;
    const int n = h.n;
    const int fans = h.boundary ? n - 1 : n;
    s.scratch.assign.clear();
    double dev = 0.0;
    const std::uint8_t own = locate(h, s.input.xy, pv, dev);
    const std::uint32_t x = node_of(s, v);
    s.scratch.assign.push_back({x, own, float(dev)});
    h.delta = dev;
    h.sp = weighted(s, x, dev);
    h.star = x;
    h.star_dev = dev;
    auto raise = [&](std::uint32_t node, double d) {
        const double w = weighted(s, node, d);
        if (w > h.sp) {
            h.sp = w;
            h.star = node;
            h.star_dev = d;
        }
    };
    // The SP so far is a lower bound of the erase's SP under any view: remembered for the next
    // evaluation and for the refiner's updates.
    auto remember = [&] {
        const std::uint32_t slot = live_slot(s, x);
        s.live.list[slot].star = h.star;
        if (s.follower)
            s.follower->evaluated(slot, float_down(h.star_dev));
    };
    if (s.input.xy) {
        // A live corner's sample sits within a rounding of the float corner: a steep (sliver)
        // triangle next to it must not read more than the bound there either. Each ring node is
        // weighed once, for its steepest triangle, and only when k / OD says that could matter (the
        // margins are a few ulp; docs/decisions/011-deferred-weighing.md).
        std::array<double, k_max_ring> steepest;
        std::fill_n(steepest.begin(), n, 0.0);
        for (int t = 0; t < h.ntri; ++t)
            for (const std::uint8_t k : {h.tri[t].a, h.tri[t].b, h.tri[t].c})
                steepest[k] = std::max(steepest[k], h.frame[t].plane.slope());
        for (int i = 0; i < n; ++i) {
            const double margin =
                rounding_margin(std::max(std::abs(h.p[i].x), std::abs(h.p[i].y)), steepest[i]);
            if (margin * s.weights.weigher.upper(h.p[i]) * k_rounded_weight > h.sp)
                raise(node_of(s, h.r[i]), margin);
        }
    }
    // The node whose deviation gave this node's last SP is tried first: when it still lies under
    // the hole (then it is one of the fan's swallowed nodes: the fan tiles the hole in xy) its
    // deviation settles most evaluations that fail without walking the fan.
    const std::uint32_t last_star = live_node(s, x).star;
    if (s.input.xy && h.sp <= limit && last_star != x &&
        s.history.record_of[last_star] >= k_absent) {
        bool inside = false;
        locate(h, s.input.xy, to_glm(node_point(s, last_star)), dev, &inside);
        if (inside) {
            raise(last_star, dev);
            if (h.sp > limit)
                return remember();
        }
    }
    // Then each fan face's worst node (its list's head, see push_swallowed): one of them is most
    // often what breaks the limit, found before any list is walked.
    for (int i = 0; i < fans && h.sp <= limit; ++i) {
        const std::int32_t u = s.faces.face_head[m.face_handle(h.h[i]).idx()];
        if (u >= 0 && std::uint32_t(u) != last_star) {
            locate(h, s.input.xy, to_glm(node_point(s, std::uint32_t(u))), dev);
            raise(std::uint32_t(u), dev);
        }
    }
    if (h.sp > limit)
        return remember();
    // A scan that finds the SP over the limit goes on to k_scan_reach times the limit. Stopped
    // at the first sample over it, the scan left an SP (the node's key and lower bound) barely
    // over the limit, which the next frame's motion took back below it: the node turned candidate
    // frame after frame as the eye drew away, each time scanning its hole again.
    if (s.input.grid_w > 0) {
        scan_hole(s, h, pv, k_scan_reach * limit, max_swallowed, known);
        return remember();
    }
    for (int i = 0; i < fans && h.sp <= limit; ++i) {
        const FH f = m.face_handle(h.h[i]);
        // A node's weight is looked up only when its deviation times the largest weight where the
        // face's swallowed nodes lie (its corners' box, within their largest deviation in z) could
        // raise the SP: each update asks for fresh weights.
        const double weight_bound =
            s.input.xy && !s.weights.unit_weights && s.faces.face_head[f.idx()] >= 0
                ? swallowed_weight_bound(s, pv, h.p[i], h.p[(i + 1) % n],
                                         s.faces.face_maxdev[f.idx()])
                : INFINITY;
        for (std::int32_t u = s.faces.face_head[f.idx()]; u >= 0; u = s.faces.next_swallowed[u]) {
            if (s.scratch.assign.size() > max_swallowed) {
                h.deferred = true;
                return remember();
            }
            const std::uint8_t t =
                locate(h, s.input.xy, to_glm(node_point(s, std::uint32_t(u))), dev);
            s.scratch.assign.push_back({std::uint32_t(u), t, float(dev)});
            if (!(dev * weight_bound > h.sp))
                continue;
            raise(std::uint32_t(u), dev);
            if (h.sp > limit)
                break; // over the bound: the exact excess does not matter
        }
    }
    return remember();
}

float key_of(const EraserState &s, const Hole &h) {
    if (s.weights.model != SpModel::paper)
        return float(h.sp);
    const glm::dvec3 p = to_glm(s.input.mesh->point(h.v));
    NodeTerms terms;
    terms.od = glm::length(p - s.weights.view.eye);
    terms.oa = observation_angle(s.weights.view, p);
    terms.delta = h.delta;
    double ring_length = 0.0;
    for (int i = 0; i < h.n; ++i)
        ring_length += glm::length(h.p[i] - p);
    terms.ration = ring_length > 0.0 ? h.delta * h.n / ring_length : 0.0;
    return float(significance(terms, Significance::paper(s.weights.view, s.weights.significance),
                              s.weights.focal_distance));
}

} // namespace tinlod::erase
