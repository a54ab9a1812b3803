// A face's check: its worst swallowed node under the current view, weighing as few of its nodes as
// the bounds allow (bands and tiles of a grid TIN, blocks of a long list, the seen bound).
#pragma once

#include "erase/state.hpp"
#include "refine/frame_state.hpp"

#include <cstdint>
#include <utility>

namespace tinlod::refine {

using erase::EraserState;
using erase::FH;

// The worst swallowed node of face f whose weighted deviation exceeds `above`, and that weighted
// deviation (-1 when none does).
std::pair<std::int32_t, double> worst_swallowed(EraserState &s, FrameState &frame, FH f,
                                                double above);

} // namespace tinlod::refine
