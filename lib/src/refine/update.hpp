// The refiner's frame step, NodeEraser::update(view, recover_above, erase_below); its algorithm
// opens tinlod/refine.hpp.
#pragma once

#include "erase/state.hpp"

#include <cstdint>

namespace tinlod::refine {

using erase::EraserState;

// The erased node to recover first on the way to erased node v: v, or the end of the chain of the
// erases v's recovery depends on, taking at each step the erased ring node nearest v (in xy for a
// TIN). The chain then stays over v, and each node recovered refines the faces around it (fewer
// recoveries than with the first erased ring node: docs/decisions/018-recovery-order.md).
// The chain is kept in s.frame.chain: the update asks again for the same v once the chain's end is
// back, and the nodes before the first one recovered since chose as they would now (a recovery
// only takes nodes out of their choice), so the walk resumes there instead of from v, which read
// each node's ring again per step.
std::uint32_t ready_dependency(EraserState &s, std::uint32_t v);

} // namespace tinlod::refine
