// The erase's last pass at a vertical bound (lib/src/erase/flip_pass.hpp), through erase_dem: on
// crops of real DEMs it leaves fewer triangles than the erase alone, every sample within the bound
// as measure_error measures it (not the pass's own check), the same outline, no fold; with a
// budget or a view it changes nothing.
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

// erase_dem from the full grid (no greedy insertion first, so both start alike).
Mesh erase_dem_from_grid(const Heightfield &hf, const Significance &model,
                         const EraseOptions &options) {
    DemEraseOptions dem;
    dem.greedy_cap = 0.0;
    return erase_dem(hf, model, options, dem);
}

} // namespace

TEST(FlipPass, FewerTrianglesWithinTheBoundOnRealCrops) {
    for (const test::CropCase &c : {test::CropCase{"dem_srtm30.tif", 40, 60, 96, 1.0},
                                    test::CropCase{"dem_srtm30.tif", 150, 120, 96, 0.5},
                                    test::CropCase{"N42E001.hgt", 300, 700, 96, 2.0},
                                    test::CropCase{"crater_u16.png", 100, 150, 96, 0.5}}) {
        SCOPED_TRACE(c.name());
        const Heightfield hf = c.load();
        EraseOptions options;
        options.tolerance = c.bound;
        const Mesh before = erase_only(hf, Significance(), options);
        const Mesh after = erase_dem_from_grid(hf, Significance(), options);
        test::expect_fewer_within(hf, before, after, c.bound);
    }
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
