// The samples a lattice TIN left out, entering it one at a time (lattice_rings.cpp): the erase
// records that make a retrieval's TIN (to_lattice_mesh) the end of a history the eraser can undo,
// so the samples the retrieval never took come in by local edits, as erased nodes do.
#pragma once

#include "tinlod/tin.hpp"

#include <cstdint>
#include <functional>

namespace tinlod {

// Called once per sample left out, in the order they enter: the sample (r * width + c), its ring
// (n nodes, counter-clockwise) and whether the ring is an open chain along the outline.
using RingVisitor =
    std::function<void(std::uint32_t node, const std::uint32_t *ring, int n, bool boundary)>;

// `tin` holds every sample of a width-wide lattice as vertex r * width + c, the ones it left out
// deleted and without edges (to_lattice_mesh), the others triangulated over the lattice's whole
// rectangle, counter-clockwise in xy. The samples left out enter level by level of the quad-tree
// (QuadLayout): each level's node centres, then its side midpoints. Each is inserted into the
// triangle that holds it (ring: its 3 corners) or into the two that share the edge it lies on
// (ring: their 4 corners; an outline edge gives the chain of its triangle's 3 corners from the
// edge's end round to its start, as EraseRecord has it), and its ring is passed to `visit`: undone
// in reverse, these insertions are erases whose records the eraser can recover from. Cost:
// O(samples) time, 32 bytes per sample while it runs.
void absent_sample_rings(const Mesh &tin, std::uint32_t width, const RingVisitor &visit);

} // namespace tinlod
