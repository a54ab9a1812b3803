// erase_dem at a fine vertical bound (docs/decisions/028-fewest-2.md): where the probe lets the
// greedy insertion run, it runs to the end (greedy_cap 1), past the 60 % of the samples it once
// stopped at (dem_srtm30 at 2 m keeps 71 %), and the erase starts from its TIN, not from the full
// grid, and leaves fewer triangles, every sample within the bound as measure_error measures it.
// Both with the flip pass, as decision 028 measured it: without it the grid's erase keeps 0.9 %
// fewer here (docs/decisions/046-flip-pass-opt-in.md).
#include "assets.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"

#include <gtest/gtest.h>

using namespace tinlod;

TEST(Fewest2, GreedyStartAtFineBoundsKeepsFewerTriangles) {
    const Heightfield hf = load_heightfield(test::asset("dem_srtm30.tif"));
    EraseOptions options;
    options.tolerance = 2.0;
    DemEraseStats stats;
    DemEraseOptions flipped;
    flipped.flip_pass = true;
    const Mesh greedy = erase_dem(hf, Significance(), options, flipped, &stats);
    DemEraseOptions from_grid = flipped;
    from_grid.greedy_cap = 0.0;
    const Mesh grid = erase_dem(hf, Significance(), options, from_grid);
    EXPECT_EQ(stats.first_stage, FirstStage::greedy);
    EXPECT_GT(stats.retrieved_nodes, hf.size() * 6 / 10);
    EXPECT_LT(greedy.n_faces(), grid.n_faces());
    const TinError error = measure_error(hf, greedy);
    EXPECT_LE(error.max_vertical, options.tolerance);
    EXPECT_EQ(error.uncovered, 0);
    EXPECT_EQ(test::count_folded_faces(greedy), 0);
    EXPECT_NEAR(test::xy_area(greedy), test::xy_area(grid), 1e-6 * test::xy_area(grid));
}
