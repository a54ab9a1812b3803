// Unit tests of the erase core's internals (lib/src/erase), each against a brute-force computation
// written here: the lattice scans and tile bounds (lattice_scan.hpp), and the batched raise of a
// band's pending samples (erase_cost.hpp); and the ear clipping of hand-built rings
// (ring_triangulation.hpp). The samples a retrieval's TIN left out, with the history options only
// the refiner sets (HistoryOptions): their rings, replayed or taken from the lattice.
#include "erase_fixtures.hpp"

#include "erase/erase_cost.hpp"
#include "erase/lattice_scan.hpp"
#include "erase/ring_triangulation.hpp"
#include "erase/state.hpp"
#include "lattice_rings.hpp"
#include "tinlod/quadtree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

using namespace tinlod;
using namespace tinlod::erase;

namespace {

// A dense grid TIN's lattice as the scans read it: w x h samples, node r * w + c at column c of row
// r, random heights and spacing (the scans need the points only, not the triangles).
struct Lattice {
    Mesh mesh;
    EraserState s;

    Lattice(std::mt19937 &rng, std::uint32_t w, std::uint32_t h) {
        std::uniform_real_distribution<double> spacing(0.1, 30.0), height(-50.0, 400.0),
            origin(-1e4, 1e4);
        const double dx = spacing(rng), dy = spacing(rng), x0 = origin(rng), y0 = origin(rng);
        for (std::uint32_t r = 0; r < h; ++r)
            for (std::uint32_t c = 0; c < w; ++c)
                mesh.add_vertex(
                    Mesh::Point(float(x0 + c * dx), float(y0 + r * dy), float(height(rng))));
        s.input.mesh = &mesh;
        s.input.grid_w = w;
        s.input.nodes = w * h;
    }
};

// Whether sample (x, y) lies in the closed triangle (a, b, c) of lattice coordinates, by the signs
// of its three edge functions (all of one sign, zero allowed); a degenerate triangle holds none.
bool inside(const std::array<std::int64_t, 6> &t, std::int64_t x, std::int64_t y) {
    const auto edge = [&](int i, int j) {
        return (t[2 * j] - t[2 * i]) * (y - t[2 * i + 1]) -
               (t[2 * j + 1] - t[2 * i + 1]) * (x - t[2 * i]);
    };
    const std::int64_t area = (t[2] - t[0]) * (t[5] - t[1]) - (t[3] - t[1]) * (t[4] - t[0]);
    if (area == 0)
        return false;
    const std::int64_t e0 = edge(0, 1), e1 = edge(1, 2), e2 = edge(2, 0);
    return area > 0 ? e0 >= 0 && e1 >= 0 && e2 >= 0 : e0 <= 0 && e1 <= 0 && e2 <= 0;
}

// A random triangle of lattice samples, often of the shapes scans get wrong: corners on the
// lattice's edges, edges along a row or a column, slivers and collinear corners.
std::array<std::uint32_t, 3> random_corners(std::mt19937 &rng, std::uint32_t w, std::uint32_t h) {
    std::uniform_int_distribution<std::uint32_t> col(0, w - 1), row(0, h - 1), kind(0, 5);
    std::array<std::uint32_t, 3> x{}, y{};
    for (int k = 0; k < 3; ++k) {
        x[k] = col(rng);
        y[k] = row(rng);
    }
    switch (kind(rng)) {
    case 0: // on the lattice's edges
        x[0] = 0;
        y[1] = h - 1;
        x[2] = w - 1;
        break;
    case 1: // an edge along a row and one along a column
        y[1] = y[0];
        x[2] = x[0];
        break;
    case 2: { // collinear: a degenerate triangle
        const std::int64_t dx = std::int64_t(x[1]) - x[0], dy = std::int64_t(y[1]) - y[0];
        if (x[0] + 2 * dx >= 0 && x[0] + 2 * dx < w && y[0] + 2 * dy >= 0 && y[0] + 2 * dy < h) {
            x[2] = std::uint32_t(x[0] + 2 * dx);
            y[2] = std::uint32_t(y[0] + 2 * dy);
        }
        break;
    }
    case 3: // a sliver: the third corner next to an edge's midpoint
        x[2] = std::min(w - 1, (x[0] + x[1]) / 2 + 1);
        y[2] = (y[0] + y[1]) / 2;
        break;
    default:
        break;
    }
    return {y[0] * w + x[0], y[1] * w + x[1], y[2] * w + x[2]};
}

} // namespace

// scan_lattice visits each sample of the closed triangle but its corners exactly once, and each in
// the xy box its band was given.
TEST(LatticeScan, VisitsExactlyTheSamplesInsideTheClosedTriangle) {
    std::mt19937 rng(47);
    std::uniform_int_distribution<std::uint32_t> side(2, 70);
    std::int64_t faces = 0, visited = 0;
    for (int lattice = 0; lattice < 40; ++lattice) {
        const std::uint32_t w = side(rng), h = side(rng);
        Lattice g(rng, w, h);
        for (int face = 0; face < 60; ++face, ++faces) {
            const auto [a, b, c] = random_corners(rng, w, h);
            const std::array<std::int64_t, 6> t = {a % w, a / w, b % w, b / w, c % w, c / w};
            std::multiset<std::uint32_t> seen;
            glm::dvec2 lo(0.0), hi(0.0);
            scan_lattice(
                g.s, a, b, c,
                [&](const glm::dvec2 &l, const glm::dvec2 &u) {
                    lo = l;
                    hi = u;
                    return 1.0;
                },
                [&](std::uint32_t u, const Mesh::Point &p, double) {
                    seen.insert(u);
                    EXPECT_EQ(p, g.mesh.point(VH(int(u))));
                    EXPECT_TRUE(p[0] >= lo.x && p[0] <= hi.x && p[1] >= lo.y && p[1] <= hi.y)
                        << "sample " << u << " outside its band's box";
                    return true;
                });
            std::multiset<std::uint32_t> expected;
            for (std::uint32_t u = 0; u < w * h; ++u)
                if (u != a && u != b && u != c && inside(t, u % w, u / w))
                    expected.insert(u);
            ASSERT_EQ(seen, expected)
                << "lattice " << w << " x " << h << ", corners " << a << ", " << b << ", " << c;
            visited += std::int64_t(seen.size());
        }
    }
    EXPECT_GT(visited, faces); // the triangles were not all empty
}

// A scan stops at the first visit that returns false, and says so.
TEST(LatticeScan, StopsWhenAVisitSaysSo) {
    std::mt19937 rng(8);
    Lattice g(rng, 40, 40);
    const std::uint32_t a = 0, b = 39, c = 39 * 40 + 20;
    int visits = 0;
    const bool whole = scan_lattice(
        g.s, a, b, c, [](const glm::dvec2 &, const glm::dvec2 &) { return 1.0; },
        [&](std::uint32_t, const Mesh::Point &, double) { return ++visits < 7; });
    EXPECT_FALSE(whole);
    EXPECT_EQ(visits, 7);
}

// Each tile's bound from tile_bounds, made from the tiles' height ranges alone, is at least the
// largest vertical distance of the face's samples in that tile to the face's plane, computed here
// from the three corners (through its normal, not TrianglePlane).
TEST(LatticeTiles, BoundEverySampleDeviationInTheirTile) {
    std::mt19937 rng(3);
    std::int64_t tiled = 0;
    for (int lattice = 0; lattice < 6; ++lattice) {
        const std::uint32_t w = 300 + 37 * std::uint32_t(lattice), h = 260;
        Lattice g(rng, w, h);
        std::vector<float> tile_z;
        build_tile_z(tile_z, g.s.input);
        for (int face = 0; face < 12; ++face) {
            std::array<std::uint32_t, 3> n = random_corners(rng, w, h);
            const auto point = [&](std::uint32_t u) { return to_glm(g.mesh.point(VH(int(u)))); };
            const glm::dvec3 pa = point(n[0]), pb = point(n[1]), pc = point(n[2]);
            const glm::dvec3 normal = glm::cross(pb - pa, pc - pa);
            if (std::abs(normal.z) < 1e-9 * glm::length(normal) + 1e-300)
                continue; // degenerate: no plane
            const auto plane = [&](double x, double y) {
                return pa.z - (normal.x * (x - pa.x) + normal.y * (y - pa.y)) / normal.z;
            };
            const Tiling tl = tiling(g.s, n[0], n[1], n[2]);
            if (!worth_tiles(tl))
                continue; // too few samples to be tiled
            const std::vector<float> tiles =
                tile_bounds(g.s, tile_z, tl, n[0], n[1], n[2], TrianglePlane(pa, pb, pc));
            ++tiled;
            const std::array<std::int64_t, 6> t = {n[0] % w, n[0] / w, n[1] % w,
                                                   n[1] / w, n[2] % w, n[2] / w};
            for (std::uint32_t u = 0; u < w * h; ++u) {
                const std::int64_t x = u % w, y = u / w;
                if (!inside(t, x, y))
                    continue;
                const std::size_t tile = std::size_t(((y - tl.row0) / k_band_rows) * tl.columns +
                                                     (x - tl.x0) / k_tile_cols);
                ASSERT_LT(tile, tiles.size());
                const glm::dvec3 q = point(u);
                EXPECT_LE(std::abs(q.z - plane(q.x, q.y)), double(tiles[tile]))
                    << "sample " << u << " of face " << n[0] << ", " << n[1] << ", " << n[2];
            }
        }
    }
    EXPECT_GT(tiled, 10);
}

// raise_pending, which weighs the pending samples largest bound first and stops early, leaves the
// SP, its node and its deviation as raising the SP by each sample in scan order would, and
// fails exactly when that raise would pass the limit.
TEST(RaisePending, MatchesRaisingOneByOneInScanOrder) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> count(0, 12), pick(0, 3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    EraserState s;
    s.weights.unit_weights = false;
    const std::uint32_t nodes = 16;
    std::int64_t failed = 0, raised = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        // Few distinct weights and deviations, so that ties between samples are common.
        s.weights.per_vertex.resize(nodes);
        for (float &x : s.weights.per_vertex)
            x = float(1 + pick(rng));
        Hole h;
        h.sp = pick(rng) * 2.0;
        h.star = 1000;
        h.star_dev = 0.5;
        const int n = count(rng);
        for (int i = 0; i < n; ++i) {
            const std::uint32_t u = std::uint32_t(rng() % nodes);
            const double dev = pick(rng) == 0 ? 0.0 : double(1 + pick(rng));
            // The band's bound is at least the weight, at times exactly it.
            const double bound =
                double(s.weights.per_vertex[u]) * (pick(rng) == 0 ? 1.0 : 1.0 + unit(rng));
            h.pending.push_back({u, dev, dev * bound, -1.0});
        }
        // evaluate raises the cost only while it is within the limit.
        const double limit = pick(rng) == 0 ? INFINITY : h.sp + 16.0 * unit(rng);

        // One by one, in scan order.
        double cost = h.sp, star_dev = h.star_dev;
        std::uint32_t star = h.star;
        bool within = true;
        for (const Hole::Pending &q : h.pending) {
            const double wd = q.dev > 0.0 ? q.dev * double(s.weights.per_vertex[q.node]) : 0.0;
            if (wd > cost) {
                cost = wd;
                star = q.node;
                star_dev = q.dev;
            }
            if (wd > limit) {
                within = false;
                break;
            }
        }

        const bool ok = raise_pending(s, h, limit);
        ASSERT_EQ(ok, within) << "trial " << trial;
        EXPECT_EQ(h.sp, cost) << "trial " << trial;
        EXPECT_EQ(h.star, star) << "trial " << trial;
        EXPECT_EQ(h.star_dev, star_dev) << "trial " << trial;
        EXPECT_TRUE(h.pending.empty());
        failed += !within;
        raised += star != 1000;
    }
    EXPECT_GT(failed, 1000);
    EXPECT_GT(raised, 1000);
}

// ---- Hand-built rings (ring_triangulation.hpp) ----

TEST(Ring, Orientation) {
    std::vector<glm::dvec2> ring = {{-1, -1}, {0, -2}, {1, -1}, {1, 1}, {-1, 1}};
    EXPECT_EQ(ring_orientation(ring), RingOrientation::ccw);
    std::reverse(ring.begin(), ring.end());
    EXPECT_EQ(ring_orientation(ring), RingOrientation::cw);
    const std::vector<glm::dvec2> line = {{0, 0}, {1, 0}, {2, 0}};
    EXPECT_EQ(ring_orientation(line), RingOrientation::degenerate);
}

TEST(Ring, ConcaveRingFirstEarNotErasable) {
    // The dent at node 3 reaches into the convex corner at node 0.
    const std::vector<glm::dvec2> ring = {{0, 0}, {4, 0}, {4, 4}, {1, 1}, {0, 4}};
    ASSERT_EQ(ring_orientation(ring), RingOrientation::ccw);
    EXPECT_FALSE(is_erasable_ear(ring, 0)); // convex, but node 3 lies inside the ear
    EXPECT_FALSE(is_erasable_ear(ring, 3)); // reflex
    EXPECT_FALSE(is_erasable_ear(ring, 1)); // node 3 lies on its edge 0-2
    EXPECT_TRUE(is_erasable_ear(ring, 2));
    const auto tris = triangulate_ring(ring);
    ASSERT_EQ(tris.size(), ring.size() - 2);
    double area = 0.0;
    for (const auto &t : tris) {
        const double a2 = orient(ring[t.a], ring[t.b], ring[t.c]);
        EXPECT_GT(a2, 0.0);
        area += a2 / 2;
        for (int j = 0; j < int(ring.size()); ++j) {
            if (j == t.a || j == t.b || j == t.c)
                continue;
            const bool inside = orient(ring[t.a], ring[t.b], ring[j]) >= 0 &&
                                orient(ring[t.b], ring[t.c], ring[j]) >= 0 &&
                                orient(ring[t.c], ring[t.a], ring[j]) >= 0;
            EXPECT_FALSE(inside) << "ring node " << j << " inside a new triangle";
        }
    }
    EXPECT_DOUBLE_EQ(area, 10.0); // the polygon's shoelace area
}

TEST(Ring, ClockwiseRingIsRefused) {
    std::vector<glm::dvec2> ring = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::reverse(ring.begin(), ring.end());
    EXPECT_TRUE(triangulate_ring(ring).empty());
}

TEST(Ring, PrefersDelaunayDiagonal) {
    // A flat rhombus: the short diagonal (1-3) is the Delaunay one.
    const std::vector<glm::dvec2> ring = {{0, 0}, {2, -0.5}, {4, 0}, {2, 0.5}};
    const auto tris = triangulate_ring(ring);
    ASSERT_EQ(tris.size(), 2u);
    for (const auto &t : tris) {
        const bool has1 = t.a == 1 || t.b == 1 || t.c == 1, has3 = t.a == 3 || t.b == 3 || t.c == 3;
        EXPECT_TRUE(has1 && has3);
    }
}

namespace {

using test::corner_view;
using test::DemAsset;
using test::invariants;
using test::Invariants;
using test::load_cropped;

} // namespace

// The samples a retrieval left out keep their insertion's ring (absent_sample_rings, replayed here
// over the whole lattice), but only the irregular ones as records: on a 2^k + 1 grid every ring is
// RegularRings' and the history holds none of them; on other sizes each ring is still the replay's.
TEST(EraseHistory, AbsentSamplesKeepOnlyTheRingsTheLatticeCannotTell) {
    for (const DemAsset &a :
         {DemAsset{"N42E001.hgt", false, 257}, DemAsset{"N42E001.hgt", false, 201}}) {
        const Heightfield hf = load_cropped(a);
        SCOPED_TRACE(std::to_string(hf.width) + "x" + std::to_string(hf.height));
        const View view = corner_view(hf);
        const Mesh lattice = to_lattice_mesh(retrieve(QuadTree(hf), view, {1.0, false}), hf);
        const RegularRings regular(std::uint32_t(hf.width), std::uint32_t(hf.height));
        std::map<std::uint32_t, ErasedNodeRing> replay;
        std::int64_t regular_ones = 0;
        absent_sample_rings(lattice, std::uint32_t(hf.width), std::uint32_t(hf.height), {},
                            [&](std::uint32_t x, const std::uint32_t *ring, int n, bool boundary) {
                                replay[x] = {{ring, ring + n}, boundary};
                                std::array<std::uint32_t, 4> guess;
                                bool chain = false;
                                const int m = regular.ring(x, guess.data(), chain);
                                regular_ones += m == n && chain == boundary &&
                                                std::equal(ring, ring + n, guess.data());
                            });
        ASSERT_GT(replay.size(), std::size_t(hf.size()) / 4);
        const auto history = [&](bool absent) {
            Mesh work = lattice;
            HistoryOptions history;
            history.absent_history = absent;
            NodeEraser eraser =
                EraserAccess::make(work, Significance::screen(view), {}, history, nullptr);
            if (absent)
                for (const auto &[x, ring] : replay) {
                    const ErasedNodeRing kept = eraser.ring(Mesh::VertexHandle(int(x)));
                    EXPECT_EQ(kept.nodes, ring.nodes) << x;
                    EXPECT_EQ(kept.boundary, ring.boundary) << x;
                }
            return double(eraser.history_bytes());
        };
        const double per_sample = (history(true) - history(false)) / double(replay.size());
        if (hf.width == 257) {
            EXPECT_EQ(regular_ones, std::int64_t(replay.size()));
            EXPECT_LT(per_sample, 2.0);
        } else {
            EXPECT_GT(regular_ones, 0);
            EXPECT_LT(regular_ones, std::int64_t(replay.size()));
        }
    }
}

// A refiner's TIN is a retrieval's (HistoryOptions::retrieval_tin): on a square 2^k + 1 grid the
// eraser takes the rings of the samples it left out from the lattice, without replaying their
// insertions. Each such ring must be the replay's, for every sample left out, whatever the view and
// the tolerance made the retrieval keep; on 201² the option must change nothing.
TEST(EraseHistory, RetrievalTinsOnPowerOfTwoGridsNeedNoReplay) {
    for (const int side : {129, 257, 513, 201}) {
        const Heightfield hf = load_cropped({"N42E001.hgt", false, side});
        const double w = (hf.width - 1) * hf.dx, h = (hf.height - 1) * hf.dy;
        View above; // high over the middle, looking almost straight down
        above.eye = {0.5 * w, 0.45 * h, hf.max_z() + 0.5 * w};
        above.at = {0.5 * w, 0.5 * h, hf.min_z()};
        View low; // low over the west third, looking east along the terrain
        low.eye = {0.3 * w, 0.5 * h, hf.max_z() + 0.02 * w};
        low.at = {w, 0.55 * h, hf.min_z()};
        const QuadTree tree(hf);
        for (const View &view : {corner_view(hf), above, low})
            for (const double tol : {0.25, 1.0, 4.0}) {
                SCOPED_TRACE(std::to_string(side) + "² at " + std::to_string(tol) + " px");
                const Mesh lattice = to_lattice_mesh(retrieve(tree, view, {tol, false}), hf);
                std::map<std::uint32_t, ErasedNodeRing> replay;
                absent_sample_rings(
                    lattice, std::uint32_t(hf.width), std::uint32_t(hf.height), {},
                    [&](std::uint32_t x, const std::uint32_t *ring, int n, bool boundary) {
                        replay[x] = {{ring, ring + n}, boundary};
                    });
                ASSERT_GT(replay.size(), 0u);
                Mesh work = lattice;
                HistoryOptions history;
                history.absent_history = true;
                history.retrieval_tin = true;
                const NodeEraser eraser =
                    EraserAccess::make(work, Significance::screen(view), {}, history, nullptr);
                EXPECT_EQ(eraser.live_nodes(), hf.size() - std::int64_t(replay.size()));
                std::int64_t differ = 0;
                for (const auto &[x, ring] : replay) {
                    const Mesh::VertexHandle v{int(x)};
                    ASSERT_TRUE(eraser.is_erased(v)) << x;
                    const ErasedNodeRing kept = eraser.ring(v);
                    differ += kept.nodes != ring.nodes || kept.boundary != ring.boundary;
                }
                EXPECT_EQ(differ, 0);
            }
    }
}

// With absent_history the samples a retrieval left out are erased nodes like any other: they enter
// by recover() in any order through a valid TIN, and recovering everything gives the whole lattice,
// whatever the grid's size (2^k + 1, odd, even).
TEST(EraseHistory, AbsentSamplesEnterInAnyOrderUntilTheLatticeIsWhole) {
    for (const DemAsset &a :
         {DemAsset{"N42E001.hgt", false, 257}, DemAsset{"N42E001.hgt", false, 201},
          DemAsset{"dem_srtm30.tif", false, 0}}) {
        const Heightfield hf = load_cropped(a);
        SCOPED_TRACE(std::to_string(hf.width) + "x" + std::to_string(hf.height));
        const View view = corner_view(hf);
        const Retrieval retrieval = retrieve(QuadTree(hf), view, {2.0, false});
        ASSERT_LT(retrieval.nodes.size(), std::size_t(hf.size()) / 2);
        Mesh work = to_lattice_mesh(retrieval, hf);
        EraseOptions options;
        options.tolerance = 4.0;
        HistoryOptions history;
        history.absent_history = true;
        NodeEraser eraser =
            EraserAccess::make(work, Significance::screen(view), options, history, nullptr);
        // Each sample's record is its insertion's ring: 3 nodes (inside a triangle), 4 (on an
        // edge) or a chain of 3 (on the outline); on a 2^k + 1 grid every centre and midpoint lies
        // on an edge of the restricted quad-tree's fans.
        std::int64_t inside = 0;
        for (auto v : work.all_vertices()) {
            if (!eraser.is_erased(v))
                continue;
            const ErasedNodeRing r = eraser.ring(v);
            EXPECT_TRUE(r.nodes.size() == 3 || (r.nodes.size() == 4 && !r.boundary)) << v.idx();
            inside += !r.boundary && r.nodes.size() == 3;
        }
        if (hf.width == 257) {
            EXPECT_EQ(inside, 0);
        }
        const EraseStats stats = eraser.erase();
        EXPECT_LE(stats.max_screen_px, options.tolerance);
        std::vector<int> out;
        for (auto v : work.all_vertices())
            if (eraser.is_erased(v))
                out.push_back(v.idx());
        EXPECT_EQ(std::int64_t(out.size()), hf.size() - eraser.live_nodes());
        std::mt19937 rng(11);
        std::shuffle(out.begin(), out.end(), rng);
        const double perimeter = 2.0 * ((hf.width - 1) * hf.dx + (hf.height - 1) * hf.dy);
        const auto check = [&](const char *stage) {
            Mesh m = eraser.mesh();
            m.garbage_collection();
            const Invariants inv = invariants(m);
            EXPECT_EQ(inv.euler, 1) << stage;
            EXPECT_EQ(inv.non_manifold, 0) << stage;
            EXPECT_NEAR(inv.boundary_length, perimeter, 1e-6 * perimeter) << stage;
            EXPECT_EQ(test::count_folded_faces(m), 0) << stage;
            EXPECT_EQ(std::int64_t(m.n_vertices()), eraser.live_nodes()) << stage;
        };
        for (std::size_t k = 0; k < out.size() / 4; ++k)
            eraser.recover(Mesh::VertexHandle(out[k]));
        check("a quarter recovered");
        eraser.recover_all();
        check("all recovered");
        EXPECT_EQ(eraser.live_nodes(), hf.size());
        EXPECT_EQ(eraser.live_triangles(), 2 * std::int64_t(hf.width - 1) * (hf.height - 1));
    }
}
