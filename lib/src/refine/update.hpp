// The refiner's frame step, NodeEraser::update (decimate.hpp).
#pragma once

#include "erase/state.hpp"

#include <cstdint>

namespace tinlod::refine {

using erase::EraserState;

// The erased node to recover first on the way to erased node v: v, or the end of the chain of the
// erases v's recovery depends on, taking at each step the erased ring node nearest v (in xy for a
// TIN). The chain then stays over v, and each node recovered refines the faces around it: on the
// three N42E001 paths at 30 frames per second, 8-11 % fewer recoveries (and 16-19 % fewer nodes
// erased again by the same update) than the first erased ring node, for 4-6 % less time per frame.
// The chain is kept in s.chain: the update asks again for the same v once the chain's end is
// back, and the nodes before the first one recovered since chose as they would now (a recovery
// only takes nodes out of their choice), so the walk resumes there instead of from v (the walks
// from v were 6 % of a 4097² fly-over's time, each node's ring read again per step).
std::uint32_t ready_dependency(EraserState &s, std::uint32_t v);

} // namespace tinlod::refine
