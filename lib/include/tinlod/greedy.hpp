// Greedy insertion of a DEM's samples into a Delaunay TIN (Garland and Heckbert, "Fast polygonal
// approximation of terrains and height fields", 1995; the method of the heightmap meshers hmm and
// delatin): from the two triangles over the lattice's corners (or a seed grid), the sample
// farthest (vertically) from the TIN is inserted, and the edges round it are flipped until the TIN
// is Delaunay again, as long as a sample is more than max_error away.
//
// tinlod uses it as the first stage of the view-independent erase at a large bound (erase_dem):
// its work follows the nodes it keeps, where the erase's follows the nodes it drops.
#pragma once

#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"

#include <cstdint>
#include <vector>

namespace tinlod {

struct GreedyTin {
    // The TIN as a retrieval has it (nodes, z and counter-clockwise triangles by sample id, for
    // to_lattice_mesh); its counters stay 0.
    Retrieval tin;
    // Per side of tin.triangles (side 3t + k runs from corner k of triangle t to corner k + 1): the
    // side running the other way, -1 on the outline.
    std::vector<std::int32_t> twin;
    bool stopped = false; // max_nodes or max_triangles was reached before max_error was
};

struct GreedyOptions {
    double max_error = 1.0;     // > 0, world units
    std::int64_t max_nodes = 0; // stop at this many nodes (0, or over 357 M: 357 M)
    // Stop before an insertion would take the triangles past this many (0: no limit). A TIN over
    // the lattice's rectangle with n nodes, b on its outline, has 2n - b - 2: an insertion inside
    // adds two, one on the outline one, so the count stops at the limit or one under it.
    std::int64_t max_triangles = 0;
    // Added to a triangle's largest deviation, times the triangle's slope (|grad z|): what a
    // consumer that rounds the TIN's coordinates to float counts on top of the deviation (the
    // node erase's rounding margin), so its own measure stays within max_error too.
    double slope_margin = 0.0;
    // The insertion starts from the nodes every seed_step samples along each row and column (and
    // the last row and column), not from the lattice's four corners (0): they spare it the scans
    // of the first few levels, over the whole lattice each, for a few more nodes
    // (docs/decisions/002-greedy-insertion.md).
    int seed_step = 0;
    // The queue's resolution: the next sample is within a factor 2^(1 / this) of the farthest
    // (2: fast, for a bound; a budget's output keeps that factor in its error, so 64 there). Over
    // 2048 / this octaves above max_error the queue no longer orders
    // (docs/decisions/002-greedy-insertion.md).
    int buckets_per_octave = 2;
};

// Inserts until every sample is within options.max_error of the TIN (vertical distance, computed
// in double from the samples' float heights, plus the slope margin), or until it holds max_nodes
// nodes or max_triangles triangles. Cost: O(samples * log(nodes)) time on a terrain, about 80 bytes
// per node.
GreedyTin greedy_tin(const Heightfield &hf, const GreedyOptions &options);

// to_sparse_lattice_mesh of the insertion's TIN, its edges paired by the insertion's twins, not
// searched for: the same mesh (docs/decisions/038-simplify-speed-7-floor.md).
Mesh to_sparse_lattice_mesh(const GreedyTin &greedy, const Heightfield &hf);

} // namespace tinlod
