// The history of the erases: one record per erased node (its ring), recovery by dependency
// closures (an erase's triangles are present exactly when all of its ring is live, as in De
// Floriani and Puppo's multi-triangulation), the samples a grid TIN left out as if erased, and
// the history's memory.
#pragma once

#include "erase/state.hpp"

namespace tinlod::erase {

// The samples a grid TIN left out (k_absent), as if erases had taken them from the whole grid
// (EraseOptions::absent_history): each gets its ring, the lattice's regular one (RegularRings) or
// a record. `retrieval_tin`: the TIN is a quad-tree retrieval's, whose rings are all regular on a
// 2^k + 1 grid.
void record_absent_samples(const Input &input, LiveSet &live, History &history, bool retrieval_tin);

// A grid TIN that holds only some of its lattice's samples (a retrieval's): the faces swallowed the
// others from the start, so each face gets its worst sample and deviation, and its corners' fan
// bounds, as an erase would have left them.
void swallow_absent(EraserState &s);

// Drops every live node's seen and low bounds (their keys may have changed without them).
void forget_nodes(LiveSet &live);

} // namespace tinlod::erase
