// The update's grid: squares in xy over the input's extent, each with bounds over the live nodes
// in it, so that an update skips whole regions (UpdateGrid). Also the huge pages an
// update's random reads want.
#pragma once

#include "erase/state.hpp"
#include "refine/frame_state.hpp"

#include <utility>
#include <vector>

namespace tinlod::refine {

using erase::EraserState;

// The box that holds cell c's live nodes and, `reach` around them, their fans' swallowed nodes.
inline std::pair<glm::dvec3, glm::dvec3> cell_box(const UpdateGrid &g, std::uint32_t c,
                                                  double reach) {
    const Cell &cell = g.cells[c];
    const double margin = reach + 1e-6 * g.cell_side; // and the rounding of cell_of's division
    const glm::dvec2 lo =
        g.grid_lo + g.cell_side * glm::dvec2(int(c) % g.grid_nx, int(c) / g.grid_nx);
    return {{lo.x - margin, lo.y - margin, double(cell.zlo) - margin},
            {lo.x + g.cell_side + margin, lo.y + g.cell_side + margin, double(cell.zhi) + margin}};
}

// Sizes the update's grid for `live` live nodes over the input's extent, at most ~4000
// cells a side however thin the outline, and puts the live nodes in its cells. The cells' fan
// bounds are their nodes' (rebuild_fans makes them when the nodes' are stale); their star bounds
// and dirty flags are the conservative ones, so the next update visits every cell once.
void regrid(UpdateGrid &grid, std::vector<FanBounds> &fans, std::int64_t live);

// The arrays an update reads at random, one entry per node (or edge, face), on huge pages: on a
// 4097² grid they span hundreds of MB, and with 4 KiB pages most reads miss the TLB. Only for a
// refiner's mesh (see rebind): a single erase gains nothing, as the collapse into huge pages costs
// what the erase saves (docs/decisions/017-huge-pages.md).
// The mesh's arrays move when they grow past their reserved room (a sparse lattice's vertices as
// samples enter, edges and faces as the TIN grows): update() advises them again then (see
// FrameState::advised). The heightfield of a sparse lattice, which its scans read, is advised too.
void advise_huge(const EraserState &s, FrameState &frame);

} // namespace tinlod::refine
