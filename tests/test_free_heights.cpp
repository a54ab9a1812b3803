// The free-heights pass after the erase (lib/src/erase/free_heights.hpp), through erase_dem
// and the CLI: on crops of real DEMs it leaves fewer triangles than with every node on its sample
// (DemEraseOptions::sample_heights, --sample-heights), every sample within the bound as
// measure_error measures it (not the pass's own check), the outline's nodes on their samples, the
// same outline, no fold.
#include "assets.hpp"
#include "erase_fixtures.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace tinlod;

namespace {

Mesh simplify(const Heightfield &hf, double bound, bool sample_heights) {
    EraseOptions options;
    options.tolerance = bound;
    DemEraseOptions dem;
    dem.sample_heights = sample_heights;
    return erase_dem(hf, Significance(), options, dem);
}

// Each node's sample height (the origin property names its sample).
float sample_height(const Heightfield &hf, const Mesh &tin, Mesh::VertexHandle v) {
    const auto origin = find_origin_property(tin);
    const std::int64_t s = tin.property(origin, v);
    return hf.z[std::size_t(s)];
}

bool on_outline(const Heightfield &hf, const Mesh &tin, Mesh::VertexHandle v) {
    const auto origin = find_origin_property(tin);
    const std::int64_t s = tin.property(origin, v), c = s % hf.width, r = s / hf.width;
    return c == 0 || r == 0 || c == hf.width - 1 || r == hf.height - 1;
}

} // namespace

TEST(FreeHeights, FewerTrianglesWithinTheBoundOnRealCrops) {
    // Two 96 x 96 crops: 30 m UTM with whole-metre heights, and SRTM 3" in the Pyrenees.
    for (const char *file : {"dem_srtm30.tif", "N42E001.hgt"})
        for (const double bound : {0.5, 2.0}) {
            SCOPED_TRACE(std::string(file) + " at " + std::to_string(bound));
            const Heightfield hf =
                test::crop(load_heightfield(test::asset(file)), 150, 120, 96, 96);
            const Mesh fixed = simplify(hf, bound, true);
            const Mesh free = simplify(hf, bound, false);
            test::expect_fewer_within(hf, fixed, free, bound);
            // The outline's nodes stay on their samples; the others moved within the bound, some of
            // them off their samples.
            std::int64_t moved = 0, outline = 0;
            for (const auto v : free.vertices()) {
                const float h = sample_height(hf, free, v), z = free.point(v)[2];
                if (on_outline(hf, free, v)) {
                    ++outline;
                    EXPECT_EQ(z, h);
                } else {
                    EXPECT_LE(std::abs(double(z) - double(h)), bound);
                    moved += z != h;
                }
            }
            EXPECT_GT(outline, 4);
            EXPECT_GT(moved, 0);
        }
}

TEST(FreeHeights, SampleHeightsKeepEveryNodeOnItsSample) {
    const Heightfield hf =
        test::crop(load_heightfield(test::asset("crater_u16.png")), 100, 150, 96, 96);
    const Mesh fixed = simplify(hf, 0.5, true);
    EXPECT_LE(measure_error(hf, fixed).max_vertical, 0.5);
    for (const auto v : fixed.vertices())
        ASSERT_EQ(fixed.point(v)[2], sample_height(hf, fixed, v));
}

TEST(FreeHeights, OnlyAtAVerticalBoundWithoutABudget) {
    const Heightfield hf =
        test::crop(load_heightfield(test::asset("dem_srtm30.tif")), 40, 60, 64, 64);
    EraseOptions budget;
    budget.tolerance = 1.0;
    budget.max_nodes = 1500;
    DemEraseOptions fixed, free;
    fixed.sample_heights = true;
    const Mesh a = erase_dem(hf, Significance(), budget, fixed);
    const Mesh b = erase_dem(hf, Significance(), budget, free);
    ASSERT_EQ(a.n_vertices(), b.n_vertices());
    ASSERT_EQ(a.n_faces(), b.n_faces());
    for (const auto v : b.vertices())
        EXPECT_EQ(a.point(v), b.point(v));
}

TEST(FreeHeights, CliFlagKeepsSampleHeights) {
    const auto fixed = test::simplify_stats("dem_srtm30.tif", "--max-error 0.5 --sample-heights"),
               free = test::simplify_stats("dem_srtm30.tif", "--max-error 0.5");
    EXPECT_LE(double(free["error"]["max_vertical"]), 0.5);
    EXPECT_LE(double(fixed["error"]["max_vertical"]), 0.5);
    EXPECT_LT(std::int64_t(free["output"]["triangles"]),
              std::int64_t(fixed["output"]["triangles"]));
}
