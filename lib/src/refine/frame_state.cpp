// The refiner's state as the erase's edits keep it up (frame_state.hpp, erase::Follower).
#include "refine/frame_state.hpp"

#include "erase/state.hpp"
#include "refine/update_grid.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tinlod::refine {

using namespace erase;

void FrameState::started(const EraserState &s) {
    const std::size_t faces = s.input.mesh->n_faces();
    seen.face_seen_dev.assign(faces, -1.0f);
    seen.face_seen.assign(faces, 0);
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
}

void FrameState::faces_compacted(std::size_t faces) {
    seen.face_seen_dev.assign(faces, -1.0f);
    seen.face_seen_dev.shrink_to_fit();
    seen.face_seen.assign(faces, 0);
    seen.face_seen.shrink_to_fit();
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
