// The refiner's frame step, NodeEraser::update(view, recover_above = tau, erase_below =
// (1 - h) tau), which follows the observer both ways with local edits:
//
//   new view: the weigher, and how far the eye moved and the axis turned since each kept view
//   recover, top down (the recoveries a frame makes are chosen here):
//       work = the faces whose swallowed nodes may exceed tau
//              (the cells' and the live nodes' fan bounds clear the rest unwalked: fan_bounds.hpp)
//       while work is not empty: f = pop(work)
//           u = f's worst swallowed node over tau, if any          (face_check.hpp)
//           x = ready_dependency(u): the erase u's recovery waits on that can be undone now
//           reinsert(x); mark x and its ring dirty; push x's faces and f
//   erase:
//       candidates = the dirty live nodes, and those whose cost may have fallen to (1 - h) tau:
//                    their star's deviation times its weight now (a lower bound of the cost) is
//                    not over it; bounds carried from earlier views settle the rest unweighed
//                    (motion_bounds.hpp)
//       sweep_dirty(candidates, (1 - h) tau): the candidates, then the rings their erases changed
//
// Afterwards every swallowed node's weighted deviation is <= tau. A frame costs a few operations
// per live node in the cells the grid cannot clear (update_grid.hpp), plus the nodes that change.
#pragma once

#include "erase/state.hpp"

#include <cstdint>

namespace tinlod::refine {

using erase::EraserState;

// The erased node to recover first on the way to erased node v: v, or the end of the chain of the
// erases v's recovery depends on, taking at each step the erased ring node nearest v (in xy for a
// TIN). The chain then stays over v, and each node recovered refines the faces around it (fewer
// recoveries than with the first erased ring node: docs/decisions/018-recovery-order.md).
// The chain is kept in s.chain: the update asks again for the same v once the chain's end is
// back, and the nodes before the first one recovered since chose as they would now (a recovery
// only takes nodes out of their choice), so the walk resumes there instead of from v, which read
// each node's ring again per step.
std::uint32_t ready_dependency(EraserState &s, std::uint32_t v);

} // namespace tinlod::refine
