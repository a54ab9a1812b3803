// The refiner's state as the erase's edits keep it up (frame_state.hpp, erase::Follower).
#include "refine/frame_state.hpp"

#include "erase/lattice_scan.hpp"
#include "erase/state.hpp"
#include "refine/update_grid.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tinlod::refine {

using namespace erase;

std::size_t FaceBlocks::bytes() const {
    std::size_t bytes = face_blocked.capacity() + tile_z.capacity() * sizeof(float) +
                        block_scratch.capacity() * 4 + block_cell_scratch.capacity() +
                        block_order_scratch.capacity() * 4;
    for (const auto &[face, tiles] : face_tiles)
        bytes += sizeof(face) + sizeof(tiles) + tiles.capacity() * sizeof(float) + 16;
    for (const auto &[face, list] : face_blocks)
        bytes += sizeof(face) + sizeof(list) + list.capacity() * sizeof(Block) + 16;
    for (const auto &[node, kept] : kept_fans) {
        bytes += sizeof(node) + sizeof(kept) + 16 + kept.head.capacity() * 4 +
                 kept.maxdev.capacity() * 4 + kept.tiles.capacity() * sizeof(kept.tiles[0]);
        for (const std::vector<float> &tiles : kept.tiles)
            bytes += tiles.capacity() * sizeof(float);
    }
    return bytes;
}

void FrameState::started(const EraserState &s) {
    const std::size_t faces = s.input.mesh->n_faces();
    seen.face_seen_dev.assign(faces, -1.0f);
    seen.face_seen.assign(faces, 0);
    blocks.face_blocked.assign(faces, 0);
    grid.grid_lo = s.input.lo;
    grid.grid_hi = s.input.hi;
    fans.reserve(std::size_t(s.live.count));
    regrid(grid, fans, s.live.count);
}

void FrameState::live_added([[maybe_unused]] std::uint32_t slot, const Mesh::Point &p) {
    assert(slot == fans.size());
    const glm::dvec3 q = to_glm(p);
    FanBounds b;
    b.p = p;
    b.cell = cell_of(grid, q);
    Cell &cell = grid.cells[b.cell];
    cell.zlo = std::min(cell.zlo, float_down(q.z));
    cell.zhi = std::max(cell.zhi, float_up(q.z));
    cell.star_dev = 0.0f;
    cell.dirty = true;
    fans.push_back(b);
}

void FrameState::live_removed(std::uint32_t slot) {
    fans[slot] = fans.back();
    fans.pop_back();
}

void FrameState::dirtied(std::uint32_t slot) {
    FanBounds &b = fans[slot];
    b.low_log = -INFINITY;
    grid.cells[b.cell].dirty = true;
}

void FrameState::parked(std::uint32_t slot) { fans[slot].low_log = INFINITY; }

void FrameState::evaluated(std::uint32_t slot, float star_dev) {
    FanBounds &b = fans[slot];
    b.star_dev = star_dev;
    Cell &cell = grid.cells[b.cell];
    cell.star_dev = std::min(cell.star_dev, star_dev);
}

void FrameState::face_added() {
    seen.face_seen_dev.push_back(-1.0f);
    seen.face_seen.push_back(0);
    blocks.face_blocked.push_back(0);
}

void FrameState::faces_compacted(std::size_t faces) {
    seen.face_seen_dev.assign(faces, -1.0f);
    seen.face_seen_dev.shrink_to_fit();
    seen.face_seen.assign(faces, 0);
    seen.face_seen.shrink_to_fit();
    // The blocks and tiles name faces by index: they go (the next scans build them again).
    blocks.face_blocked.assign(faces, 0);
    blocks.face_blocked.shrink_to_fit();
    blocks.face_blocks.clear();
    blocks.face_tiles.clear();
}

// A shallow history's erase whose fan covers many samples of a grid TIN keeps what its faces knew
// (KeptFan), which its re-insert gives back unscanned (k_kept_fan_samples, erase/tuning.hpp).
void FrameState::fan_erasing(const EraserState &s, std::uint32_t x, const Hole &h, const FH *face,
                             int fans) {
    if (s.input.grid_w == 0 || !s.input.history.shallow_history ||
        lattice_inside(s, h) <= k_kept_fan_samples)
        return;
    KeptFan &kept = blocks.kept_fans[x];
    kept.head.resize(std::size_t(fans));
    kept.maxdev.resize(std::size_t(fans));
    kept.tiles.resize(std::size_t(fans));
    for (int t = 0; t < fans; ++t) {
        const std::int32_t f = face[t].idx();
        kept.head[std::size_t(t)] = s.faces.face_head[std::size_t(f)];
        kept.maxdev[std::size_t(t)] = s.faces.face_maxdev[std::size_t(f)];
        const auto tiles = blocks.face_tiles.find(f);
        if (tiles != blocks.face_tiles.end())
            kept.tiles[std::size_t(t)] = std::move(tiles->second);
        else
            kept.tiles[std::size_t(t)].clear();
    }
}

bool FrameState::fan_restoring(FaceIndex &faces, std::uint32_t x, const FH *face, int fans) {
    const auto kept = blocks.kept_fans.find(x);
    if (kept == blocks.kept_fans.end())
        return false;
    // The fan's faces are the triangles they were at the erase, holding the same samples.
    for (int i = 0; i < fans; ++i) {
        const std::int32_t f = face[i].idx();
        faces.face_head[std::size_t(f)] = kept->second.head[std::size_t(i)];
        faces.face_maxdev[std::size_t(f)] = kept->second.maxdev[std::size_t(i)];
        if (!kept->second.tiles[std::size_t(i)].empty()) {
            blocks.face_tiles[f] = std::move(kept->second.tiles[std::size_t(i)]);
            blocks.face_blocked[std::size_t(f)] = 1;
        }
    }
    blocks.kept_fans.erase(kept);
    return true;
}

// Widens each corner's bounds to cover its own new triangles, as fan_extent would from them (their
// farthest corner, plus their largest deviation): bounds from the whole hole made the updates walk
// fans that the node's own bounds clear (docs/decisions/006-fan-bounds.md).
void FrameState::fans_widened(const EraserState &s, const glm::dvec3 *p, const std::uint32_t *ids,
                              int count, const RingTriangle *tri, const float *dev, int ntri) {
    if (fans_stale)
        return;
    std::array<double, k_max_ring + 1> far2;
    std::array<float, k_max_ring + 1> most;
    std::fill_n(far2.begin(), count, 0.0);
    std::fill_n(most.begin(), count, 0.0f);
    for (int t = 0; t < ntri; ++t) {
        const std::uint8_t c[3] = {tri[t].a, tri[t].b, tri[t].c};
        for (int k = 0; k < 3; ++k) {
            const std::uint8_t i = c[k];
            for (int j = 1; j < 3; ++j) {
                const glm::dvec3 d = p[c[(k + j) % 3]] - p[i];
                far2[i] = std::max(far2[i], glm::dot(d, d));
            }
            most[i] = std::max(most[i], dev[t]);
        }
    }
    for (int i = 0; i < count; ++i) {
        if (s.history.record_of[ids[i]] >= 0)
            continue;
        FanBounds &b = fans[live_slot(s, ids[i])];
        b.seen_log = INFINITY;
        b.fan_exact = false;
        b.reach = std::max(b.reach, float_up(std::sqrt(far2[i]) + double(most[i])));
        b.fan_dev = std::max(b.fan_dev, most[i]);
        Cell &cell = grid.cells[b.cell];
        cell.reach = std::max(cell.reach, b.reach);
        cell.fan_dev = std::max(cell.fan_dev, b.fan_dev);
    }
}

void FrameState::erased(bool shrunk) {
    if (shrunk)
        fans.shrink_to_fit();
    forget_nodes();
}

void FrameState::view_changed() {
    std::fill(seen.face_seen_dev.begin(), seen.face_seen_dev.end(), -1.0f);
    forget_nodes();
}

// Drops every live node's seen and low bounds (their keys may have changed without them).
void FrameState::forget_nodes() {
    for (FanBounds &b : fans) {
        b.seen_log = INFINITY;
        b.low_log = -INFINITY;
    }
}

} // namespace tinlod::refine
