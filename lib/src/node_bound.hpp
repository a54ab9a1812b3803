// A quad-tree node's own error bound over the rows of a band (quadtree.cpp): what QuadTree builds
// over the whole grid at once and the store's windowed build (store.cpp) over bands of rows, the
// largest deviation of a sample from the node's fans, a maximum over the rows and so the same
// however the rows are banded.
#pragma once

#include "float_rounding.hpp"
#include "tinlod/quadtree.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace tinlod {

// Rows r0..r1 (inclusive) of a grid, every column, row-major. Samples of other rows are read only
// at the column and row bounds of level key_level, from `keys` (row-major over those bounds); a
// band that is the whole grid needs none.
struct GridRows {
    const float *band = nullptr;
    int width = 0;
    std::uint32_t r0 = 0, r1 = 0;
    const float *keys = nullptr;
    const QuadLayout *layout = nullptr;
    int key_level = 0;

    const float *row(std::uint32_t r) const { return band + std::size_t{r - r0} * width; }
    float at(std::uint32_t c, std::uint32_t r) const {
        if (r >= r0 && r <= r1)
            return row(r)[c];
        const AxisSplit &x = layout->x, &y = layout->y;
        return keys[std::size_t{y.bound_index(key_level, r)} * (x.count(key_level) + 1) +
                    x.bound_index(key_level, c)];
    }
};

struct OwnBound {
    double error = 0.0;
    float zmin = std::numeric_limits<float>::max();
    float zmax = std::numeric_limits<float>::lowest();
    void box(float z) {
        zmin = std::min(zmin, z);
        zmax = std::max(zmax, z);
    }
};

// The own error of the node spanning columns x0..x1 and rows y0..y1 over its samples in rows
// ra..rb (a node of 2 x 2 cells: all its rows), and with `box` their z box. Its fans' corners,
// centre and side midpoints are read through rows.at: the bounds of the level below the node's.
OwnBound own_bound(const GridRows &rows, std::uint32_t x0, std::uint32_t x1, std::uint32_t y0,
                   std::uint32_t y1, std::uint32_t ra, std::uint32_t rb, bool box);

// Throws Error when a grid is too small or too large for a quad-tree (2x2 to 2^31 samples).
void check_quad_grid(int width, int height);

// Node (d, i, j)'s bound from its own error and, when it has children (d + 1 < levels - 1),
// theirs: `child(i', j')` gives the bound of node (d + 1, i', j'), and the children's boxes make
// the node's box.
template <class ChildBound>
NodeBound node_bound(const QuadLayout &lay, int d, std::uint32_t i, std::uint32_t j, OwnBound own,
                     ChildBound &&child) {
    float children = 0.0f;
    if (d + 1 < lay.levels() - 1) {
        const std::uint32_t cx = lay.x.first_child(d, i), cy = lay.y.first_child(d, j);
        const std::uint32_t ncx = lay.x.length(d, i) >= 2 ? 2 : 1;
        const std::uint32_t ncy = lay.y.length(d, j) >= 2 ? 2 : 1;
        for (std::uint32_t b = 0; b < ncy; ++b)
            for (std::uint32_t a = 0; a < ncx; ++a) {
                const NodeBound c = child(cx + a, cy + b);
                children = std::max(children, c.error);
                own.box(c.zmin);
                own.box(c.zmax);
            }
    }
    return {std::max(float_up(own.error), children), own.zmin, own.zmax};
}

} // namespace tinlod
