// The measure of a tile and its repair in place (tile_measure.hpp).
#include "tile_measure.hpp"

#include "../triangle_plane.hpp"

#include <array>
#include <limits>
#include <unordered_map>

namespace tinlod::tiles {

namespace {

double decoded_height(const Quantized &q, std::uint16_t code) {
    return q.min_h + double(code) / double(k_quantized_max) * (q.max_h - q.min_h);
}

} // namespace

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

} // namespace tinlod::tiles
