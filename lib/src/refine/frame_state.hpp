// The parts of the eraser's state that only the refiner's frame step reads (FrameState): the
// update's grid (UpdateGrid), the view bounds the updates carry over (ViewBounds), and what an
// update keeps between its steps. EraserState holds one (frame); the stages that read only these
// take them, not the whole state.
#pragma once

#include "erase/tuning.hpp"
#include "tinlod/view.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tinlod::refine {

// A square of the grid in xy that lets an update skip whole regions: bounds over the live nodes in
// it, kept conservative between updates (raised, or lowered for star_dev, as the nodes change).
struct Cell {
    float fan_dev = 0.0f;                  // >= every live node's fan_dev
    float reach = 0.0f;                    // >= every live node's reach
    float star_dev = 0.0f;                 // <= every live node's star_dev
    float zlo = INFINITY, zhi = -INFINITY; // the heights of every node in it, live or erased
    bool dirty = true;                     // some live node in it may be dirty
};

// The update's grid (update_grid.hpp). Invariants: cells has grid_nx * grid_ny entries, cells of
// side cell_side from grid_lo, row by row, over the input's extent in xy (grid_lo to grid_hi),
// sized for grid_live live nodes (see regrid); each live node's LiveNode::cell is the cell that
// holds its point (cell_of), and each cell's bounds hold for its nodes (see Cell).
struct UpdateGrid {
    std::vector<Cell> cells;
    std::vector<std::uint8_t> cell_visit; // update's scratch: the cells that may matter
    glm::dvec2 grid_lo{0.0}, grid_hi{0.0};
    double cell_side = 1.0;
    std::int64_t grid_live = 0;
    int grid_nx = 1, grid_ny = 1;

    std::size_t bytes() const { return cells.capacity() * sizeof(Cell) + cell_visit.capacity(); }
};

// The cell of point p.
inline std::uint32_t cell_of(const UpdateGrid &g, const glm::dvec3 &p) {
    const int cx = std::clamp(int(std::floor((p.x - g.grid_lo.x) / g.cell_side)), 0, g.grid_nx - 1);
    const int cy = std::clamp(int(std::floor((p.y - g.grid_lo.y) / g.cell_side)), 0, g.grid_ny - 1);
    return std::uint32_t(cy * g.grid_nx + cx);
}

// The view bounds the updates carry over (motion_bounds.hpp), for the screen model.
// Invariants: face_seen_dev and face_seen have an entry per face; face_seen_dev[f] >= 0 bounds f's
// swallowed nodes' weighted deviation under the view of update face_seen[f] >> 1 (negative: none
// since the face last changed; the low bit of face_seen[f]: they lay inside the view cone then,
// see weight_growth). When the eye moves by d and the axis turns by a, a node's weight
// k / distance * peripheral(angle to the axis) grows by at most
// (1 + d / distance') * exp((a + asin(d / distance')) / falloff), so a face whose nodes were
// within the bound by that much is cleared without a scan (docs/decisions/007-seen-bounds.md).
// seen_views holds the views of the last k_seen_views updates, update u's in slot
// u % k_seen_views; an older bound is dropped.
struct ViewBounds {
    std::vector<float> face_seen_dev;
    std::vector<std::uint32_t> face_seen;
    std::array<View, erase::k_seen_views> seen_views;
    // For the update under way, per slot of seen_views: how far the eye has moved and the axis
    // turned since that view, and whether a bound made then carries over (the same lens).
    struct Since {
        double moved = 0.0, turn = 0.0;
        bool ok = false;
    };
    std::array<Since, erase::k_seen_views> since;
    std::uint32_t updates = 0; // update() calls so far

    std::size_t bytes() const {
        return face_seen_dev.capacity() * 4 + face_seen.capacity() * 4 + sizeof(seen_views);
    }
};

// The refiner's part of the eraser's state.
// Invariants: with fans_stale, the live nodes' and cells' fan bounds (LiveNode::reach, fan_dev,
// Cell::fan_dev, reach) are not kept, else they hold for the fans as they stand; advised is all
// null, or where the mesh's vertex, edge and face arrays were when they were last advised.
struct FrameState {
    // The live nodes' and cells' fan bounds are not kept while this is set: only an update reads
    // them, so the constructor and erase() leave them, and the first update after them builds them
    // from the fans (rebuild_fans), as keeping them cost a one-off erase time for nothing
    // (docs/decisions/006-fan-bounds.md).
    bool fans_stale = true;
    UpdateGrid grid;
    // Where the mesh's vertex, edge and face arrays were when rebind() advised huge pages for them
    // (all null: never, as for a one-off erase).
    std::array<const void *, 3> advised{};
    ViewBounds seen;
    std::vector<std::uint32_t> chain; // the update's last dependency chain (see ready_dependency)

    std::size_t bytes() const { return grid.bytes() + seen.bytes(); }
};

} // namespace tinlod::refine
