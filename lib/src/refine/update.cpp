// The refiner's frame step (update.hpp).
#include "refine/update.hpp"

#include "erase/edits.hpp"
#include "erase/erase_cost.hpp"
#include "erase/history.hpp"
#include "erase/lattice_scan.hpp"
#include "erase/sweep.hpp"
#include "refine/face_check.hpp"
#include "refine/fan_bounds.hpp"
#include "refine/motion_bounds.hpp"
#include "refine/update_grid.hpp"
#include "tinlod/focal.hpp"
#include "tinlod/util.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tinlod::refine {

using namespace erase;

std::uint32_t ready_dependency(const EraserState &s, FrameState &frame, std::uint32_t v) {
    std::vector<std::uint32_t> &chain = frame.chain;
    if (chain.empty() || chain.front() != v) {
        chain.assign(1, v);
    } else {
        std::size_t kept = 1;
        while (kept < chain.size() && s.history.record_of[chain[kept]] >= 0)
            ++kept;
        chain.resize(kept);
    }
    const glm::dvec3 target = to_glm(node_point(s, v));
    for (;;) {
        const std::uint32_t at = chain.back();
        std::array<std::uint32_t, 4> scratch;
        const ErasedRing erased = erased_ring(s.history, at, scratch);
        const std::uint32_t *ring = erased.nodes;
        std::uint32_t next = at;
        double nearest = INFINITY;
        for (int i = 0; i < erased.size; ++i)
            if (s.history.record_of[ring[i]] >= 0) {
                glm::dvec3 d = to_glm(node_point(s, ring[i])) - target;
                if (s.input.xy)
                    d.z = 0.0;
                if (glm::dot(d, d) < nearest) {
                    nearest = glm::dot(d, d);
                    next = ring[i];
                }
            }
        if (next == at)
            return at;
        chain.push_back(next);
    }
}

namespace {

// The update's grid sized for the live nodes, and their fan bounds built, if need be.
void prepare(const EraserState &s, FrameState &frame) {
    if (s.live.count > k_regrid_ratio * frame.grid.grid_live ||
        k_regrid_ratio * s.live.count < frame.grid.grid_live)
        regrid(frame.grid, frame.fans, s.live.count);
    if (frame.fans_stale)
        rebuild_fans(s, frame);
}

// The new view's weigher, and how far the eye has moved and the axis turned since each kept view
// (ViewBounds::since), for the bounds carried over.
void new_view(EraserState &s, FrameState &frame, const View &view) {
    s.weights.view = view;
    if (s.weights.model == SpModel::paper)
        s.weights.focal_distance = std::max(focal_point(*s.input.mesh, view).distance, 1e-9);
    s.weights.weigher = Weigher(s.weights.view, s.weights.significance);
    new_weights(s, false);
    frame.seen.seen_views[++frame.seen.updates % k_seen_views] = view;
    for (std::uint32_t i = 0; i < k_seen_views; ++i) {
        const View &then = frame.seen.seen_views[i];
        ViewBounds::Since &d = frame.seen.since[i];
        d.ok = then.fov_deg == view.fov_deg && then.viewport_w == view.viewport_w &&
               then.viewport_h == view.viewport_h;
        d.moved = glm::length(view.eye - then.eye);
        d.turn = std::acos(std::clamp(glm::dot(then.axis(), view.axis()), -1.0, 1.0));
    }
}

// The recover worklist: every face whose swallowed nodes may exceed `recover_above` (their
// largest deviation over the distance to the box they lie in says so, without visiting them). The
// grid skips the cells whose bounds clear every node in them; the walk over the live nodes
// rebuilds those bounds (widen_fans raises them as the update changes fans).
std::vector<FH> seed_recover(const EraserState &s, FrameState &frame, double recover_above) {
    std::vector<std::uint8_t> &visit = frame.grid.cell_visit;
    visit.resize(frame.grid.cells.size());
    for (std::uint32_t c = 0; c < std::uint32_t(frame.grid.cells.size()); ++c) {
        Cell &cell = frame.grid.cells[c];
        const auto [lo, hi] = cell_box(frame.grid, c, double(cell.reach));
        visit[c] = cell.fan_dev > 0.0f &&
                   double(cell.fan_dev) * s.weights.weigher.bound(lo, hi) * k_rounded_weight >
                       recover_above;
        cell.fan_dev = 0.0f;
        cell.reach = 0.0f;
    }
    std::vector<FH> work;
    const double log_recover = std::log(recover_above);
    for (std::uint32_t i = 0; i < std::uint32_t(frame.fans.size()); ++i) {
        FanBounds &l = frame.fans[i];
        if (visit[l.cell] && !fan_cleared(s, frame, l, recover_above, log_recover))
            seed_fan(s, frame, i, recover_above, work);
        Cell &cell = frame.grid.cells[l.cell];
        cell.fan_dev = std::max(cell.fan_dev, l.fan_dev);
        cell.reach = std::max(cell.reach, l.reach);
    }
    return work;
}

// Recovers top down until no face of the worklist exceeds `recover_above`: a face whose worst node
// does gets back the erase that node's recovery waits for that can be undone now, alone, and is
// checked again with the faces of the node re-inserted. The new fan often brings the worst node
// within the bound before its whole closure is back (bottom up, most of a closure was erased again
// by the same update). Returns the nodes recovered.
std::vector<std::uint32_t> recover_faces(EraserState &s, FrameState &frame, std::vector<FH> work,
                                         double recover_above, UpdateStats &stats) {
    const Mesh &m = *s.input.mesh;
    const std::int64_t entered = s.counters.entered, fans_kept = s.counters.fans_kept;
    std::vector<std::uint32_t> recovered;
    frame.chain.clear(); // the erases since the last update may have changed any choice
    while (!work.empty()) {
        const FH f = work.back();
        work.pop_back();
        if (m.status(f).deleted())
            continue;
        ++stats.faces_checked;
        const std::int32_t u = worst_swallowed(s, frame, f, recover_above).first;
        if (u < 0)
            continue;
        const std::uint32_t x = ready_dependency(s, frame, std::uint32_t(u));
        reinsert(s, x);
        ++stats.recovered;
        s.live.flags[x] |= k_recovered;
        recovered.push_back(x);
        // Re-evaluated by this update's erase: a node recovered only because a worse one depended
        // on it may cost little, and a key of "significant" would keep it forever. So are its ring
        // nodes: their fans gave x its faces back, so their erase costs changed and the bounds on
        // them (FanBounds::star_dev, low_log) no longer hold: left as they were, the TIN kept more
        // nodes than its erase bound asks for (docs/decisions/018-recovery-order.md).
        mark_dirty(s, x);
        for (auto r : m.vv_range(vh(s, x)))
            if (!(s.live.flags[node_of(s, r)] & k_locked))
                mark_dirty(s, node_of(s, r));
        for (auto g : m.vf_range(vh(s, x)))
            work.push_back(g);
        if (!m.status(f).deleted())
            work.push_back(f);
    }
    stats.entered = s.counters.entered - entered;
    stats.fans_kept = s.counters.fans_kept - fans_kept;
    return recovered;
}

// The live nodes whose cost may have fallen to `erase_below`: the grid skips the cells where no
// node is dirty and every node's cost is over the bound (the least star deviation times the least
// weight in the box the stars lie in says so), and each node's lower bound on its cost, carried
// from the view it was made under, settles most of the rest without a weight.
std::vector<std::uint32_t> unsettled_nodes(const EraserState &s, FrameState &frame,
                                           double erase_below) {
    std::vector<std::uint8_t> &visit = frame.grid.cell_visit;
    for (std::uint32_t c = 0; c < std::uint32_t(frame.grid.cells.size()); ++c) {
        Cell &cell = frame.grid.cells[c];
        const auto [lo, hi] = cell_box(frame.grid, c, double(cell.reach));
        visit[c] =
            cell.dirty || !(double(cell.star_dev) * s.weights.weigher.lower(lo, hi) > erase_below);
        cell.star_dev = INFINITY;
    }
    std::vector<std::uint32_t> unsettled;
    const double log_below = std::log(erase_below);
    for (std::uint32_t i = 0; i < std::uint32_t(frame.fans.size()); ++i) {
        const FanBounds &l = frame.fans[i];
        Cell &cell = frame.grid.cells[l.cell];
        cell.star_dev = std::min(cell.star_dev, l.star_dev);
        if (!visit[l.cell])
            continue;
        // A node that is not dirty (mark_dirty drops low_log) and whose cost cannot have fallen
        // to the bound since it was last known: the star lies within reach of the node.
        if (l.low_log == INFINITY)
            continue; // parked
        if (l.low_log > -INFINITY) {
            if (const ViewBounds::Since *d = since(s, frame, l.low_at)) {
                // The shrink outside the view cone bounds the one inside it: the cone test (a
                // square root and a division per node) only when that bound does not settle the
                // node (docs/decisions/007-seen-bounds.md).
                const glm::dvec3 p = to_glm(l.p), r(double(l.reach));
                const double falloff = s.weights.weigher.falloff();
                if (moved_within(s.weights.view.eye, p, r.x, d->moved,
                                 double(l.low_log) - log_below - d->turn / falloff,
                                 4.0 / 3.0 + k_asin_quarter / falloff))
                    continue;
                const double nearest = glm::length(p - s.weights.view.eye) - r.x;
                if (double(l.low_log) - log_shrink(s.weights.weigher, *d, nearest, false) >
                        log_below ||
                    (s.weights.weigher.in_cone(p - r, p + r) &&
                     double(l.low_log) - log_shrink(s.weights.weigher, *d, nearest, true) >
                         log_below))
                    continue;
            }
        }
        unsettled.push_back(i);
    }
    return unsettled;
}

// The candidates of the update's erase among the unsettled nodes: those whose star's deviation
// times its weight now (a lower bound of the cost) does not keep them over `erase_below`, marked
// dirty; the others keep that bound as their key.
std::vector<std::uint32_t> pick_candidates(EraserState &s, FrameState &frame,
                                           const std::vector<std::uint32_t> &unsettled,
                                           double erase_below, UpdateStats &stats) {
    std::vector<std::uint32_t> candidates;
    // Their flags and their star's height are each a cache miss, asked for k_ahead nodes ahead
    // (docs/decisions/009-prefetching.md).
    for (std::size_t i = 0; i < unsettled.size(); ++i) {
        if (i + k_ahead < unsettled.size()) {
            const LiveNode &ahead = s.live.list[unsettled[i + k_ahead]];
            __builtin_prefetch(&s.live.flags[ahead.node]);
            if (s.input.lattice)
                __builtin_prefetch(&s.input.lattice->z[ahead.star]);
        }
        const std::uint32_t slot = unsettled[i];
        const LiveNode &l = s.live.list[slot];
        const std::uint32_t x = l.node;
        if (s.live.flags[x] & k_locked)
            continue;
        const float key = node_key(s.live, slot);
        if (!std::isfinite(key))
            continue; // its hole cannot be re-triangulated: only a change of its ring can help
        if (!(s.live.flags[x] & k_dirty)) {
            // The cost under this view is at least the star's deviation times its weight now.
            FanBounds &b = frame.fans[slot];
            const double least = double(b.star_dev) * weight_of(s, l.star);
            if (least > erase_below) {
                store_node_key(s.live, slot, float_down(least));
                remember_low(s, frame, b, least);
                continue;
            }
        }
        ++stats.candidates;
        s.live.flags[x] |= k_dirty;
        candidates.push_back(x);
    }
    return candidates;
}

// What the update's sweep keeps for the updates that follow (SweepObserver): a node that costs too
// much keeps that cost as a lower bound (remember_low), an erase's ring nodes get back seen bounds
// (seen_before, carry_seen); and it counts the erases of nodes this update recovered.
class KeepBounds final : public SweepObserver {
  public:
    KeepBounds(const EraserState &s, FrameState &frame) : s_(s), frame_(frame) {}
    void too_costly(std::uint32_t slot, double cost) override {
        remember_low(s_, frame_, frame_.fans[slot], cost);
    }
    void erasing(std::uint32_t x, const Hole &h) override {
        reerased += (s_.live.flags[x] & k_recovered) != 0;
        seen_before(s_, frame_, h, seen_);
    }
    void erased(const Hole &h) override { carry_seen(s_, frame_, h, seen_); }

    std::int64_t reerased = 0;

  private:
    const EraserState &s_;
    FrameState &frame_;
    std::array<double, k_max_ring> seen_; // the ring's seen bounds before the erase under way
};

// The sweep over the candidates and the rings their erases change, at `erase_below`.
void erase_candidates(EraserState &s, FrameState &frame, std::vector<std::uint32_t> candidates,
                      double erase_below, UpdateStats &stats) {
    assert(!frame.fans_stale && s.follower == &frame); // the cap reads the fans' reach
    KeepBounds keep(s, frame);
    const std::int64_t evaluations = s.counters.evaluations;
    stats.erased = sweep_dirty(s, erase_below, std::move(candidates), k_update_cap, 0, &keep);
    stats.evaluations = s.counters.evaluations - evaluations;
    stats.reerased = keep.reerased;
}

// The update's flags go (the sweep left no live node dirty), and the mesh's arrays are advised
// again if one grew out of its room.
void finish(EraserState &s, FrameState &frame, const std::vector<std::uint32_t> &recovered) {
    const Mesh &m = *s.input.mesh;
    for (const std::uint32_t x : recovered)
        s.live.flags[x] &= std::uint8_t(~k_recovered);
    for (Cell &cell : frame.grid.cells)
        cell.dirty = false;
    if (frame.advised[0] && (frame.advised[0] != m.points() ||
                             (m.n_edges() > 0 && frame.advised[1] != &m.edge(EH(0))) ||
                             (m.n_faces() > 0 && frame.advised[2] != &m.face(FH(0)))))
        advise_huge(s, frame);
}

} // namespace

Engine::Engine(Mesh &mesh, const Significance &model, const EraseOptions &options,
               const HistoryOptions &history)
    : eraser(EraserAccess::make(mesh, model, options, history, &frame)) {}

void Engine::compact() { erase::compact(state()); }

void Engine::rebind(Mesh &mesh) {
    EraserState &s = state();
    assert(mesh.n_vertices() == s.input.mesh->n_vertices() &&
           mesh.n_faces() == s.faces.face_head.size());
    s.input.mesh = &mesh;
    advise_huge(s, frame);
    if (frame.fans_stale)
        rebuild_fans(s, frame); // here, not in the first update (docs/decisions/006-fan-bounds.md)
    if (s.input.grid_w > 0 && frame.blocks.tile_z.empty())
        build_tile_z(frame.blocks.tile_z, s.input); // and these (a pass over every sample)
}

UpdateStats Engine::update(const View &view, double recover_above, double erase_below) {
    EraserState &s = state();
    assert(s.weights.model != SpModel::vertical && erase_below <= recover_above);
    if (s.history.absent_for_good)
        throw std::logic_error("refine::Engine::update: the samples the input TIN left out need "
                               "HistoryOptions::absent_history to follow a view");
    UpdateStats stats;
    prepare(s, frame);
    Stopwatch clock;
    new_view(s, frame, view);
    stats.weights_ms = clock.ms();
    clock.reset();
    const std::vector<std::uint32_t> recovered =
        recover_faces(s, frame, seed_recover(s, frame, recover_above), recover_above, stats);
    stats.recover_ms = clock.ms();
    clock.reset();
    erase_candidates(
        s, frame,
        pick_candidates(s, frame, unsettled_nodes(s, frame, erase_below), erase_below, stats),
        erase_below, stats);
    finish(s, frame, recovered);
    stats.erase_ms = clock.ms();
    return stats;
}

std::size_t Engine::bytes() const { return eraser.history_bytes() + frame.bytes(); }

} // namespace tinlod::refine
