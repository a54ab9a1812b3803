// The flip pass at a vertical bound (lib/src/erase/flip_pass.hpp), through erase_dem and the CLI
// when asked for (DemEraseOptions::flip_pass, --flip-pass; off by default): on crops of real DEMs
// it leaves fewer triangles than the erase alone and than erase_dem without it, every sample
// within the bound as measure_error measures it (not the pass's own check), the same outline, no
// fold; with a budget or a view it changes nothing.
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

// The erase alone from the full grid (what erase_dem did before the pass), as erase_dem returns it.
Mesh erase_only(const Heightfield &hf, const Significance &model, const EraseOptions &options) {
    Mesh grid = grid_tin(hf);
    NodeEraser(grid, model, options).erase();
    return live_copy(grid);
}

// erase_dem from the full grid (no greedy insertion first, so both start alike), with the pass.
Mesh erase_dem_from_grid(const Heightfield &hf, const Significance &model,
                         const EraseOptions &options) {
    DemEraseOptions dem;
    dem.greedy_cap = 0.0;
    dem.flip_pass = true;
    return erase_dem(hf, model, options, dem);
}

// Crops of real DEMs at a fine bound each, where the pass erases nodes.
const test::CropCase k_crops[] = {{"dem_srtm30.tif", 40, 60, 96, 1.0},
                                  {"dem_srtm30.tif", 150, 120, 96, 0.5},
                                  {"N42E001.hgt", 300, 700, 96, 2.0},
                                  {"crater_u16.png", 100, 150, 96, 0.5}};

// On every crop at its bound, `after(hf, options)` keeps fewer triangles than `before(hf,
// options)`, within the bound, on the same outline, without a fold.
template <class Before, class After> void expect_fewer_on_crops(Before before, After after) {
    for (const test::CropCase &c : k_crops) {
        SCOPED_TRACE(c.name());
        const Heightfield hf = c.load();
        EraseOptions options;
        options.tolerance = c.bound;
        test::expect_fewer_within(hf, before(hf, options), after(hf, options), c.bound);
    }
}

} // namespace

TEST(FlipPass, FewerTrianglesWithinTheBoundOnRealCrops) {
    expect_fewer_on_crops([](const Heightfield &hf,
                             const EraseOptions &o) { return erase_only(hf, Significance(), o); },
                          [](const Heightfield &hf, const EraseOptions &o) {
                              return erase_dem_from_grid(hf, Significance(), o);
                          });
}

TEST(FlipPass, AskedForKeepsFewerTrianglesThanWithout) {
    // On the samples' heights, so that only the flip pass differs.
    DemEraseOptions without;
    without.sample_heights = true;
    DemEraseOptions with = without;
    with.flip_pass = true;
    expect_fewer_on_crops(
        [&](const Heightfield &hf, const EraseOptions &o) {
            return erase_dem(hf, Significance(), o, without);
        },
        [&](const Heightfield &hf, const EraseOptions &o) {
            return erase_dem(hf, Significance(), o, with);
        });
}

TEST(FlipPass, CliFlagRunsThePass) {
    const auto plain = test::simplify_stats("dem_srtm30.tif", "--max-error 1 --sample-heights"),
               flipped = test::simplify_stats("dem_srtm30.tif",
                                              "--max-error 1 --sample-heights --flip-pass");
    EXPECT_LE(double(flipped["error"]["max_vertical"]), 1.0);
    EXPECT_LT(std::int64_t(flipped["output"]["triangles"]),
              std::int64_t(plain["output"]["triangles"]));
}

TEST(FlipPass, OnlyAtAVerticalBoundWithoutABudget) {
    const Heightfield hf =
        test::crop(load_heightfield(test::asset("dem_srtm30.tif")), 40, 60, 64, 64);
    EraseOptions budget;
    budget.tolerance = 1.0;
    budget.max_nodes = 1500;
    const Mesh a = erase_only(hf, Significance(), budget);
    const Mesh b = erase_dem_from_grid(hf, Significance(), budget);
    EXPECT_EQ(a.n_faces(), b.n_faces());
    EXPECT_EQ(a.n_vertices(), b.n_vertices());
}
