// erase_dem at a fine vertical bound (docs/decisions/028-fewest-2.md): where the probe lets the
// greedy insertion run, it runs to the end (greedy_cap 1) and the erase starts from its TIN, not
// from the full grid, and leaves fewer triangles, every sample within the bound as measure_error
// measures it (crater_u16 at 1 m: the probe's windows keep about a third of their samples).
#include "assets.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"

#include <gtest/gtest.h>

using namespace tinlod;

TEST(Fewest2, GreedyStartAtFineBoundsKeepsFewerTriangles) {
    LoadOptions lo;
    lo.cell = 1.0;
    const Heightfield hf = load_heightfield(test::asset("crater_u16.png"), lo);
    EraseOptions options;
    options.tolerance = 1.0;
    DemEraseStats stats;
    const Mesh greedy = erase_dem(hf, Significance(), options, DemEraseOptions(), &stats);
    DemEraseOptions from_grid;
    from_grid.greedy_cap = 0.0;
    const Mesh grid = erase_dem(hf, Significance(), options, from_grid);
    EXPECT_EQ(stats.first_stage, FirstStage::greedy);
    EXPECT_LT(greedy.n_faces(), grid.n_faces());
    const TinError error = measure_error(hf, greedy);
    EXPECT_LE(error.max_vertical, options.tolerance);
    EXPECT_EQ(error.uncovered, 0);
    EXPECT_EQ(test::count_folded_faces(greedy), 0);
    EXPECT_NEAR(test::xy_area(greedy), test::xy_area(grid), 1e-6 * test::xy_area(grid));
}
