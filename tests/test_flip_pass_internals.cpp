// The flip pass's cover test ruled out by a walk towards the hull (cover_ruled_out,
// lib/src/erase/flip_pass.hpp), against a brute force over every triple of nodes: on the rings and
// two-rings of the nodes an erase leaves on real crops, it never rules out a polygon some triangle
// of which holds the node's sample near its height, and it rules out most of those none does.
#include "erase/flip_pass.hpp"
#include "erase/tin_arrays.hpp"
#include "erase_fixtures.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/significance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace tinlod;

namespace {

struct Polygon {
    std::vector<std::int64_t> x, y; // relative to the node's sample
    std::vector<double> h;
    double z = 0.0;
    int start[3] = {-1, -1, -1};
};

// Whether some triangle over three of the points whose closed triangle holds the origin (either
// orientation) has its plane within stop of z there, in long double from exact areas; `slack`
// widens or narrows the band so that rounding cannot decide.
bool brute_covers(const Polygon &p, double stop, long double slack) {
    const int n = int(p.x.size());
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b)
            for (int c = b + 1; c < n; ++c) {
                const std::int64_t s0 = p.x[a] * p.y[b] - p.y[a] * p.x[b],
                                   s1 = p.x[b] * p.y[c] - p.y[b] * p.x[c],
                                   s2 = p.x[c] * p.y[a] - p.y[c] * p.x[a];
                const bool ccw = s0 >= 0 && s1 >= 0 && s2 >= 0 && s0 + s1 + s2 > 0;
                const bool cw = s0 <= 0 && s1 <= 0 && s2 <= 0 && s0 + s1 + s2 < 0;
                if (!ccw && !cw)
                    continue;
                const long double area = (long double)(s0 + s1 + s2);
                const long double h = ((long double)p.h[a] * s1 + (long double)p.h[b] * s2 +
                                       (long double)p.h[c] * s0) /
                                      area;
                if (std::abs(h - (long double)p.z) <= (long double)stop + slack)
                    return true;
            }
    return false;
}

// Node 0, the last node after it less than a half-turn on, the next: a triangle holding the origin
// when the first `ring` points go around it counter-clockwise (as the pass starts its walk).
void ring_start(Polygon &p, int ring) {
    const auto cross = [&](int a, int b) { return p.x[a] * p.y[b] - p.y[a] * p.x[b]; };
    int b = 1;
    while (b + 1 < ring && cross(0, b + 1) > 0)
        ++b;
    if (b + 1 < ring && cross(0, b) >= 0 && cross(b, b + 1) >= 0 && cross(b + 1, 0) >= 0 &&
        cross(0, b) + cross(b, b + 1) + cross(b + 1, 0) > 0) {
        p.start[0] = 0;
        p.start[1] = b;
        p.start[2] = b + 1;
    }
}

// Each interior node's ring, and its ring followed by the other nodes of its neighbours' rings
// (not in angle order, some in one direction from it: as the pass's widened polygons are), of
// the TIN the erase leaves on the crop.
std::vector<Polygon> polygons(const Heightfield &hf, double bound) {
    Mesh grid = grid_tin(hf);
    EraseOptions options;
    options.tolerance = bound;
    NodeEraser(grid, Significance(), options).erase();
    const Mesh tin = live_copy(grid);
    const erase::TinArrays a = erase::tin_arrays(tin, hf);
    std::vector<Polygon> out;
    std::vector<std::int32_t> ring, star, other_ring, other_star;
    std::vector<int> edge, other_edge;
    for (std::size_t v = 0; v < a.sample.size(); ++v) {
        if (!a.star(std::int32_t(v), k_max_ring, ring, star, edge))
            continue;
        Polygon p;
        p.z = a.z[v];
        const auto add = [&](std::int32_t u) {
            p.x.push_back(a.col[std::size_t(u)] - a.col[v]);
            p.y.push_back(a.row[std::size_t(u)] - a.row[v]);
            p.h.push_back(a.z[std::size_t(u)]);
        };
        for (const std::int32_t u : ring)
            add(u);
        ring_start(p, int(ring.size()));
        out.push_back(p);
        std::vector<std::int32_t> seen = ring;
        seen.push_back(std::int32_t(v));
        for (const std::int32_t u : ring)
            if (a.star(u, k_max_ring, other_ring, other_star, other_edge))
                for (const std::int32_t w : other_ring)
                    if (std::find(seen.begin(), seen.end(), w) == seen.end() &&
                        p.x.size() < std::size_t(k_max_ring)) {
                        seen.push_back(w);
                        add(w);
                    }
        out.push_back(p);
    }
    return out;
}

} // namespace

TEST(FlipPassCover, RuledOutOnlyWhereNoTriangleCoversOnRealCrops) {
    for (const test::CropCase &c : {test::CropCase{"dem_srtm30.tif", 40, 60, 64, 1.0},
                                    test::CropCase{"dem_srtm30.tif", 150, 120, 64, 5.0},
                                    test::CropCase{"N42E001.hgt", 300, 700, 64, 2.0},
                                    test::CropCase{"crater_u16.png", 100, 150, 64, 0.5}}) {
        SCOPED_TRACE(c.name());
        const Heightfield hf = c.load();
        const std::vector<Polygon> all = polygons(hf, c.bound);
        int started = 0, open = 0, ruled_out = 0;
        for (const Polygon &p : all) {
            if (p.start[0] < 0)
                continue;
            ++started;
            int start[3] = {p.start[0], p.start[1], p.start[2]};
            const bool out = erase::cover_ruled_out(p.x.data(), p.y.data(), p.h.data(),
                                                    int(p.x.size()), p.z, c.bound, start);
            // Ruled out: no triangle comes within the bound, nor within a hair over it.
            if (out) {
                EXPECT_FALSE(brute_covers(p, c.bound, 1e-6L));
            }
            if (!brute_covers(p, c.bound, -1e-6L)) {
                ++open;
                ruled_out += out;
            }
        }
        EXPECT_GT(started, 1000);
        EXPECT_GT(open, 100);
        // The walk reaches the hull's facet: it misses only the nodes some triangle's plane passes
        // below and another's above (a saddle).
        EXPECT_GT(ruled_out, open / 2) << ruled_out << " of " << open;
    }
}
