// The erase's drivers: the sweep, and the queue of the paper model.
//
// The sweep (screen and vertical models, with a bound tau or a node budget N) passes over the
// nodes in storage order, which is spatially coherent, so the half-edge arrays and the swallowed
// lists stay in cache (a queue jumps across the terrain; docs/decisions/013-sweep.md):
//
//   order = the live, unlocked nodes by id
//   sweep(limit):                                   one pass (sweep_pass)
//       for x in order, while more than the pass's stop remain live:
//           if x is dirty or key(x) <= limit:       key(x): a lower bound of x's cost
//               cost = evaluate(x)                  the SP of the erase (erase_cost.hpp)
//               if cost <= limit: retriangulate(x), mark x's ring dirty (edits.hpp)
//               else key(x) = cost
//   tau alone:                                      tolerance passes
//       for k = tau_rungs .. 1: sweep(tau / ratio^k)      cheap erases first (meshes, refiner)
//       repeat sweep(tau) until it erases nothing
//   budget N:                                       rungs (docs/decisions/014-budget-rungs.md)
//       limit = the (live - 2N)-th smallest first cost, sampled
//       while live > 2N and limit < tau: sweep(limit) once, limit *= 2     coarse rungs
//       while live > N and limit <= tau:                                   fine rungs
//           sweep the dirty nodes and those with key <= limit, then the rings their erases
//           changed, until none is left (sweep_dirty)
//           limit = max(1.05 limit, the least key)
//
// The queue (the paper model, whose key is not a cost, or no bound at all): rank every node by
// its key, then pop the least while its erase stays within tau; a dirty node is re-evaluated at the
// top and goes back with its new cost. An update (refine/update.hpp) sweeps only the nodes that
// changed, at its bound alone (sweep_dirty).
#pragma once

#include "erase/state.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tinlod::erase {

// rank: every erasable node enters the queue keyed by the cost of its erase.
void rank_nodes(EraserState &s);

// erase: pops the least significant node while its erase stays within the tolerance.
std::int64_t erase_loop(EraserState &s);

// The input nodes the xy fan of x covers, estimated by its area at the input's mean density (low
// where the input does not fill its box).
double covered_estimate(const EraserState &s, std::uint32_t x);

// What a sweep tells a caller that keeps bounds on the live nodes from sweep to sweep (the
// refiner's update, refine/update.cpp). A one-off erase has none.
class SweepObserver {
  public:
    virtual ~SweepObserver() = default;
    // The erase cost of the live node in `slot` under the current view is `cost`, over the
    // sweep's limit.
    virtual void too_costly(std::uint32_t slot, double cost) = 0;
    // The erase of live node x, whose hole is h (s.scratch.hole), is about to be made.
    virtual void erasing(std::uint32_t x, const Hole &h) = 0;
    // That erase is made (h is its hole still).
    virtual void erased(const Hole &h) = 0;
};

// The sweep over the nodes of `list` only, then over the rings their erases changed, at `limit`
// alone, until `stop_at` live nodes remain: its cost follows the nodes that changed (an update's
// rungs below the limit cost time for no fewer nodes: docs/decisions/013-sweep.md). Fans over
// `cap` swallowed nodes are left as they are (see sweep_node; a cap needs the follower's bounds on
// the fans, EraserState::follower). `observer` (may be null) hears of the costs and erases. Returns
// the erases made.
std::int64_t sweep_dirty(EraserState &s, double limit, std::vector<std::uint32_t> list,
                         std::size_t cap, std::int64_t stop_at = 0,
                         SweepObserver *observer = nullptr);

// The sweep at the top of this file, for the SP models whose key is the cost (not `paper`).
// Returns the erases made.
std::int64_t sweep_erase(EraserState &s);

} // namespace tinlod::erase
