// The samples a lattice TIN left out, entering it one at a time (lattice_rings.cpp): the erase
// records that make a retrieval's TIN (to_lattice_mesh) the end of a history the eraser can undo,
// so the samples the retrieval never took come in by local edits, as erased nodes do.
#pragma once

#include "tinlod/quadtree.hpp"
#include "tinlod/tin.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace tinlod {

// Called once per sample left out, in the order they enter: the sample (r * width + c), its ring
// (n nodes, counter-clockwise) and whether the ring is an open chain along the outline.
using RingVisitor =
    std::function<void(std::uint32_t node, const std::uint32_t *ring, int n, bool boundary)>;

// `tin` holds samples of a width x height lattice, triangulated over the lattice's whole
// rectangle, counter-clockwise in xy: vertex v is sample sample_of[v] (r * width + c), or sample v
// when sample_of is empty (then the samples it left out are vertices too, deleted and without
// edges, as to_lattice_mesh has them). The samples left out enter level by level of the quad-tree
// (QuadLayout): each level's node centres, then its side midpoints. Each is inserted into the
// triangle that holds it (ring: its 3 corners) or into the two that share the edge it lies on
// (ring: their 4 corners; an outline edge gives the chain of its triangle's 3 corners from the
// edge's end round to its start, as ErasedNodeRing has it), and its ring is passed to `visit`:
// undone in reverse, these insertions are erases whose records the eraser can recover from. A ring
// that closes starts at its least sample id (a chain keeps its order). Cost: O(samples) time, 32
// bytes per sample while it runs.
void absent_sample_rings(const Mesh &tin, std::uint32_t width, std::uint32_t height,
                         std::span<const std::uint32_t> sample_of, const RingVisitor &visit);

// The ring absent_sample_rings gives a sample where the lattice is regular (every 2^k + 1 grid),
// from the sample's place in the quad-tree alone: so the eraser keeps only the rings that differ
// (an irregular layout's, as 1201 x 1201), not 20-24 bytes for every sample left out.
//  - a node's centre lies on the diagonal its parent's fan split the node along: its ring is the
//    node's four corners;
//  - a side's midpoint lies on the side, between the fans of the two nodes that share it: its
//    ring is the side's ends and the two nodes' centres, or on the outline the chain from the
//    side's end round the one node's centre to its start.
// The node and side are the first of the quad-tree's order to hold the sample (see
// absent_sample_rings). Cost: O(levels) per ring, one byte per row and column.
class RegularRings {
  public:
    RegularRings(std::uint32_t width, std::uint32_t height);
    // Whether every sample a quad-tree retrieval's TIN leaves out on such a lattice gets the
    // regular ring from absent_sample_rings: a square 2^k + 1 grid, whose every node splits into
    // four equal ones (its centre lies on both its diagonals, each side's midpoint on the side).
    static bool regular_for_retrievals(std::uint32_t width, std::uint32_t height);
    // Writes sample's ring to `ring` (room for 4) and returns its size (3 or 4); `boundary` tells
    // a chain. The sample must not be a corner of the lattice.
    int ring(std::uint32_t sample, std::uint32_t *ring, bool &boundary) const;
    std::size_t bytes() const;

  private:
    std::uint32_t w_, h_;
    QuadLayout layout_;
    std::vector<std::uint8_t> level_x_, level_y_; // the first level whose bounds hold a column/row
};

} // namespace tinlod
