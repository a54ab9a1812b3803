// Unit tests of the quad-tree's internals (lib/src/working_set.hpp): the heights a TIN's bound
// rests on, against every sample of a real DEM.
#include "assets.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/screen_weight.hpp"
#include "working_set.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace tinlod;
using namespace tinlod::test;

namespace {

struct NamedView {
    std::string name;
    View view;
};

// Near the ground looking across the terrain, and high above looking down.
std::vector<NamedView> low_and_high(const Heightfield &hf) {
    const double ex = (hf.width - 1) * hf.dx, ey = (hf.height - 1) * hf.dy;
    const double relief = std::max(double(hf.max_z()) - hf.min_z(), 1.0);
    const int c = hf.width / 10, r = hf.height / 10;
    View low, high;
    low.eye = {c * hf.dx, r * hf.dy, hf.at(c, r) + std::max(2.0, 0.01 * relief)};
    low.at = {0.6 * ex, 0.7 * ey, hf.at(hf.width * 6 / 10, hf.height * 7 / 10)};
    high.eye = {0.5 * ex, 0.45 * ey, hf.max_z() + std::max(ex, ey)};
    high.at = {0.5 * ex, 0.5 * ey, hf.min_z()};
    return {{"low", low}, {"high", high}};
}

} // namespace

namespace {

// The nodes of `level` whose (inclusive) rectangle holds sample (c, r): up to two per axis.
std::vector<std::size_t> nodes_holding(const QuadLayout &lay, int level, std::uint32_t c,
                                       std::uint32_t r) {
    auto along = [&](const AxisSplit &axis, std::uint32_t s, std::uint32_t last) {
        const std::uint32_t k = axis.interval_of(level, std::min(s, last - 1));
        std::vector<std::uint32_t> out{k};
        if (s == axis.lo(level, k) && k > 0)
            out.push_back(k - 1);
        return out;
    };
    std::vector<std::size_t> out;
    for (const std::uint32_t j : along(lay.y, r, std::uint32_t(lay.height - 1)))
        for (const std::uint32_t i : along(lay.x, c, std::uint32_t(lay.width - 1)))
            out.push_back(std::size_t(j) * lay.x.count(level) + i);
    return out;
}

} // namespace

TEST(HeightWorkingSet, EverySampleOutsideTheNeededBlocksIsWithinTheBound) {
    // The blocks the working set leaves out are cleared by node bounds alone: every sample in them
    // under a face of the TIN must be within tau, weighted as the erase weighs it. The TIN is
    // erase_dem's to 4 tau, so that many samples are not, and those must lie in needed blocks.
    // Checked at every sample of N42E001, from the low and the high view.
    const Heightfield hf = load_heightfield(asset("N42E001.hgt"));
    const QuadTree tree(hf);
    const QuadLayout &lay = tree.layout();
    const int level = level_for_cells(lay, 16);
    ASSERT_LE(lay.x.length(level, 0), 16u);
    const SignificanceOptions screen;
    constexpr double tau = 1.0;
    for (const NamedView &nv : low_and_high(hf)) {
        EraseOptions eo;
        eo.tolerance = 4 * tau;
        const Mesh tin = erase_dem(hf, Significance::screen(nv.view), eo);
        const WorkingSet ws = height_working_set(tree, tin, nv.view, screen, tau, level);
        ASSERT_EQ(ws.needed.size(), lay.level_nodes(level));
        EXPECT_EQ(ws.count, std::count(ws.needed.begin(), ws.needed.end(), 1)) << nv.name;
        std::int64_t cleared = 0, over = 0;
        for (const auto f : tin.faces()) {
            std::array<glm::dvec3, 3> p;
            int k = 0;
            for (const auto v : tin.fv_range(f)) {
                const Mesh::Point &q = tin.point(v);
                p[k++] = glm::dvec3(q[0], q[1], q[2]);
            }
            const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
            const auto c0 = int(std::ceil(std::min({p[0].x, p[1].x, p[2].x}) / hf.dx - 1e-6));
            const auto c1 = int(std::floor(std::max({p[0].x, p[1].x, p[2].x}) / hf.dx + 1e-6));
            const auto r0 = int(std::ceil(std::min({p[0].y, p[1].y, p[2].y}) / hf.dy - 1e-6));
            const auto r1 = int(std::floor(std::max({p[0].y, p[1].y, p[2].y}) / hf.dy + 1e-6));
            for (int r = r0; r <= r1; ++r)
                for (int c = c0; c <= c1; ++c) {
                    const Mesh::Point g = grid_point(hf, c, r);
                    const glm::dvec3 s(g[0], g[1], g[2]);
                    bool inside = true;
                    for (int i = 0; i < 3 && inside; ++i) {
                        const glm::dvec3 a = p[i], b = p[(i + 1) % 3];
                        inside = (b.x - a.x) * (s.y - a.y) - (b.y - a.y) * (s.x - a.x) >=
                                 -1e-3 * hf.dx * glm::length(b - a);
                    }
                    if (!inside)
                        continue;
                    const double plane =
                        p[0].z - (n.x * (s.x - p[0].x) + n.y * (s.y - p[0].y)) / n.z;
                    const double weighted =
                        std::abs(s.z - plane) * screen_weight(nv.view, s, screen);
                    over += weighted > tau;
                    const bool needed = std::ranges::any_of(
                        nodes_holding(lay, level, std::uint32_t(c), std::uint32_t(r)),
                        [&](std::size_t node) { return ws.needed[node] != 0; });
                    if (needed)
                        continue;
                    ++cleared;
                    ASSERT_LE(weighted, tau * (1.0 + 1e-6))
                        << nv.name << ": sample (" << c << ", " << r << ") in a cleared block";
                }
        }
        // The check has teeth both ways: many samples lie in cleared blocks, many are over tau.
        EXPECT_GT(cleared, 10000) << nv.name;
        EXPECT_GT(over, 1000) << nv.name;
        // A looser bound needs fewer blocks; the grid's own TIN, whose faces hold no sample but
        // their corners, needs none.
        EXPECT_LT(height_working_set(tree, tin, nv.view, screen, 4 * tau, level).count, ws.count)
            << nv.name;
        EXPECT_EQ(height_working_set(tree, grid_tin(hf), nv.view, screen, tau, level).count, 0)
            << nv.name;
    }
}
