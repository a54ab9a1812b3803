// The heights a TIN's bound rests on: which blocks of a quad-tree's heights a refiner that paged
// them would keep in memory (bench_fly's working-set columns; tested in test_quadtree_internals).
// Defined in quadtree.cpp, on the tree's node bounds.
#pragma once

#include "tinlod/quadtree.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <cstdint>
#include <vector>

namespace tinlod {

// The first level whose nodes span at most `cells` cells on each side (at most levels() - 2, the
// deepest with bounds).
int level_for_cells(const QuadLayout &layout, int cells);

// Which blocks of heights (the nodes of one level) a TIN over the tree's grid needs in memory to
// show, from a view, that every sample under its faces is within tol_px of them (weighted by the
// erase's screen weight: k / distance times the peripheral factor): what a refiner that paged its
// heights would have to keep. A node clears the samples of a face inside it without reading them
// when its bound plus the largest distance of its fan's five points (corners and centre) from the
// face's plane, times the largest weight over its box, is within tol_px: its bound holds for the
// fan without side midpoints, and the fan minus the plane is linear on each of the fan's four
// triangles, so it is largest at their corners. Nodes are tried from the root down to `level`; a
// node of `level` that no such test cleared is needed when a sample inside or on the face, other
// than its corners, lies in it.
struct WorkingSet {
    int level = 0;
    std::vector<std::uint8_t> needed; // per node of `level`, row-major (j, i): 1 when needed
    std::int64_t count = 0;           // nodes needed
    double share() const { return needed.empty() ? 0.0 : double(count) / double(needed.size()); }
};
// `tin`: live faces over the grid in grid_point's frame (deleted elements are skipped).
WorkingSet height_working_set(const QuadTree &tree, const Mesh &tin, const View &view,
                              const SignificanceOptions &significance, double tol_px, int level);

} // namespace tinlod
