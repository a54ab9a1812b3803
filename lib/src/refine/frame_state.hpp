// The refiner's state beside the eraser's (FrameState): its bounds on each live node's fan
// (FanBounds), the update's grid (UpdateGrid), the view bounds the updates carry over
// (ViewBounds), and what an update keeps between its steps. The erase's edits keep it up through
// erase::Follower, which FrameState implements; a one-off erase has none.
#pragma once

#include "erase/follower.hpp"
#include "erase/tuning.hpp"
#include "tinlod/view.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace tinlod::refine {

// A square of the grid in xy that lets an update skip whole regions: bounds over the live nodes in
// it, kept conservative between updates (raised, or lowered for star_dev, as the nodes change).
struct Cell {
    float fan_dev = 0.0f;                  // >= every live node's FanBounds::fan_dev
    float reach = 0.0f;                    // >= every live node's FanBounds::reach
    float star_dev = 0.0f;                 // <= every live node's FanBounds::star_dev
    float zlo = INFINITY, zhi = -INFINITY; // the heights of every node in it, live or erased
    bool dirty = true;                     // some live node in it may be dirty
};

// What an update needs to know of a live node without walking its fan, by the node's slot in the
// eraser's live list (FrameState::fans follows the list's swap-removals: live_removed). In an array
// of its own, not in erase::LiveNode, so a one-off erase neither carries nor maintains it; the
// update's walks over the live nodes read it in slot order, as they read the live list.
struct FanBounds {
    Mesh::Point p; // its point (an update reads it for every node it visits)
    // The deviation of the node's LiveNode::star at its last evaluation: the cost under any later
    // view is at least star_dev times the star's weight there while the fan stands.
    float star_dev = 0.0f;
    // Bounds on the fan's swallowed nodes: each lies within `reach` of the node (3-D) and deviates
    // at most `fan_dev` from its face. Raised as the fan changes, tightened when an update walks
    // the fan.
    float reach = 0.0f;
    float fan_dev = 0.0f;
    std::uint32_t cell = 0; // its cell of the update's grid (UpdateGrid)
    // For the screen model's updates, as logarithms (see ViewBounds::face_seen_dev for the motion
    // factor that carries them to a later view): under the view of update seen_at, every node the
    // faces it seeds (see seed_fan) swallowed had a weighted deviation <= exp(seen_log) (+inf:
    // none known, dropped when the fan changes but by an update's erase, see carry_seen); under
    // the view of update low_at, its erase cost was >= exp(low_log) (-inf: none known, dropped
    // when it turns dirty; +inf: parked, see park).
    float seen_log = INFINITY;
    float low_log = -INFINITY;
    // The update numbers in 31 bits, each beside a flag, so that FanBounds, LiveNode and the
    // keys take no more than LiveNode alone took (after 2^31 updates since() drops every bound).
    std::uint32_t seen_at : 31 = 0;
    std::uint32_t seen_cone : 1 = 0; // the fan's swallowed nodes were inside the view cone then
    std::uint32_t low_at : 31 = 0;
    std::uint32_t fan_exact : 1 = 0; // reach and fan_dev are fan_extent's for the fan as it stands
};

// What the faces of an erased node's fan knew of the samples they held, for the re-insert that
// brings the same triangles back (see reinsert): per fan face, in ring order, its worst sample,
// their largest deviation and its tile bounds (empty when it had none, see lattice_tiles).
struct KeptFan {
    std::vector<std::int32_t> head;
    std::vector<float> maxdev;
    std::vector<std::vector<float>> tiles;
};

// A run of a long swallowed list (see build_blocks).
struct Block {
    std::int32_t head;   // its first node
    std::uint32_t count; // its length
    double dev;          // >= the deviation of each of its nodes from the face
    glm::dvec3 lo, hi;   // the box of its nodes
};

// What the refiner keeps on large faces, so that a face check weighs few of their nodes
// (face_check.hpp): a long list's blocks, a grid TIN's tile bounds, and what the faces of an erased
// fan knew.
// Invariants: face_blocked has an entry per face (deleted ones included), 1 exactly when
// face_blocks or face_tiles holds the face; a face's blocks are runs of its list, and its tiles
// bound its samples' deviation; both go when its swallowed nodes change (face_changed).
struct FaceBlocks {
    std::vector<std::uint8_t> face_blocked;
    std::unordered_map<std::int32_t, std::vector<Block>> face_blocks; // see build_blocks
    std::unordered_map<std::int32_t, std::vector<float>> face_tiles;  // see lattice_tiles
    // A grid TIN's lattice tiles (see erase::build_tile_z): the least and largest height of each,
    // made by rebind() or when a face is first tiled.
    std::vector<float> tile_z;
    // A shallow history's erased nodes whose fan covered more than k_kept_fan_samples samples of a
    // grid TIN: per fan face, what it knew of its samples (see KeptFan), by node.
    std::unordered_map<std::uint32_t, KeptFan> kept_fans;
    // build_blocks' scratch.
    std::vector<std::int32_t> block_scratch;
    std::vector<std::uint8_t> block_cell_scratch;
    std::vector<std::int32_t> block_order_scratch;

    // Face f's swallowed nodes change: its blocks and tiles go.
    void drop(std::int32_t f) {
        if (face_blocked[std::size_t(f)]) {
            face_blocked[std::size_t(f)] = 0;
            face_blocks.erase(f);
            face_tiles.erase(f);
        }
    }

    std::size_t bytes() const;
};

// The update's grid (update_grid.hpp). Invariants: cells has grid_nx * grid_ny entries, cells of
// side cell_side from grid_lo, row by row, over the input's extent in xy (grid_lo to grid_hi),
// sized for grid_live live nodes (see regrid); each live node's FanBounds::cell is the cell that
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

// The refiner's state beside the eraser's, which the erase's edits keep up (erase::Follower).
// Invariants: fans has an entry per live node, by its slot in the eraser's live list; with
// fans_stale, the live nodes' and cells' fan bounds (FanBounds::reach, fan_dev, Cell::fan_dev,
// reach) are not kept, else they hold for the fans as they stand; advised is all null, or where the
// mesh's vertex, edge and face arrays were when they were last advised.
class FrameState final : public erase::Follower {
  public:
    // The live nodes' and cells' fan bounds are not kept while this is set: only an update reads
    // them, so the constructor and erase() leave them, and the first update after them builds them
    // from the fans (rebuild_fans), as keeping them cost the first erase time for nothing
    // (docs/decisions/006-fan-bounds.md).
    bool fans_stale = true;
    std::vector<FanBounds> fans;
    UpdateGrid grid;
    // Where the mesh's vertex, edge and face arrays were when rebind() advised huge pages for them
    // (all null: never).
    std::array<const void *, 3> advised{};
    ViewBounds seen;
    FaceBlocks blocks;
    std::vector<std::uint32_t> chain; // the update's last dependency chain (see ready_dependency)

    std::size_t bytes() const {
        return fans.capacity() * sizeof(FanBounds) + grid.bytes() + seen.bytes() + blocks.bytes();
    }

    // erase::Follower (frame_state.cpp).
    void started(const erase::EraserState &s) override;
    void live_added(std::uint32_t slot, const Mesh::Point &p) override;
    void live_removed(std::uint32_t slot) override;
    void dirtied(std::uint32_t slot) override;
    void parked(std::uint32_t slot) override;
    void evaluated(std::uint32_t slot, float star_dev) override;
    float reach(std::uint32_t slot) const override { return fans[slot].reach; }
    void face_changed(erase::FH f) override {
        seen.face_seen_dev[f.idx()] = -1.0f;
        blocks.drop(f.idx());
    }
    void face_added() override;
    void faces_compacted(std::size_t faces) override;
    void fans_widened(const erase::EraserState &s, const glm::dvec3 *p, const std::uint32_t *ids,
                      int count, const erase::RingTriangle *tri, const float *dev,
                      int ntri) override;
    void fan_erasing(const erase::EraserState &s, std::uint32_t x, const erase::Hole &h,
                     const erase::FH *face, int fans) override;
    bool fan_restoring(erase::FaceIndex &faces, std::uint32_t x, const erase::FH *face,
                       int fans) override;
    void erasing() override { fans_stale = true; }
    void erased(bool shrunk) override;
    void view_changed() override;

  private:
    void forget_nodes();
};

} // namespace tinlod::refine
