// The history of the erases: one record per erased node (its ring), recovery by dependency
// closures (an erase's triangles are present exactly when all of its ring is live, as in De
// Floriani and Puppo's multi-triangulation), the samples a grid TIN left out as if erased, and
// the history's memory.
#pragma once

#include "erase/state.hpp"

namespace tinlod::erase {

// The samples a grid TIN left out (k_absent), as if erases had taken them from the whole grid
// (HistoryOptions::absent_history): each gets its ring, the lattice's regular one (RegularRings) or
// a record. `retrieval_tin`: the TIN is a quad-tree retrieval's, whose rings are all regular on a
// 2^k + 1 grid.
void record_absent_samples(const Input &input, LiveSet &live, History &history, bool retrieval_tin);

// A grid TIN that holds only some of its lattice's samples (a retrieval's): the faces swallowed the
// others from the start, so each face gets its worst sample and deviation, and its corners' fan
// bounds, as an erase would have left them.
void swallow_absent(EraserState &s);

// Drops the erased edges and faces from the mesh's arrays (an erase from a grid keeps a few
// percent of them): edge and face handles change, vertex handles stay (erased vertices remain,
// marked deleted: they name the history), except with EraseOptions::lattice, where the erased
// vertices go too and the live ones move down in order. Re-inserts then add what they need.
// OpenMesh keeps the arrays' capacity; to give the memory back, copy the mesh and rebind. The
// live nodes' keys and stamps move to LiveSet::slot_key and slot_stamp (node_keys), for updates.
void compact(EraserState &s);

} // namespace tinlod::erase
