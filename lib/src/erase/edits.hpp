// The erase and its inverse as in-place half-edge edits. A node of valence n frees 3 edges and 2
// faces (a boundary node 2 and 1) and the remaining n-3 spoke edges and n-2 faces become the new
// diagonals and triangles; freed elements are kept on free lists and re-used by the re-insert, so
// no library-side OpenMesh call (and no garbage collection) runs per erase. The erase is inverted
// as a vertex split in the manner of Hoppe's view-dependent progressive meshes.
#pragma once

#include "erase/state.hpp"

namespace tinlod::erase {

// retriangulate: replaces the fan of the evaluated hole by its new triangles in place, moves the
// swallowed nodes to the triangles that now cover them and records the erase.
void retriangulate(EraserState &s);

// Re-inserts erased node x, whose ring nodes are all live: the faces inside its ring become its
// fan again, the diagonals and two free edges its spokes.
void reinsert(EraserState &s, std::uint32_t x);

} // namespace tinlod::erase
