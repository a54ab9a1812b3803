// A tile's measure and repair (tile_build.cpp builds the tile, then calls them): every covered post
// inside the tile against the quantized TIN as a decoder reads it, and the posts over the bound
// made vertices in place.
#pragma once
#include "geodesy.hpp"

#include "tinlod/tiles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tinlod::tiles {

// A vertex of the tile as it is assembled: its u/v place and its height, a whole multiple of the
// tile's step (an edge's, of a coarser one).
struct Vertex {
    int u = 0, v = 0;
    double h = 0.0;
};

struct Assembly {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> triangles;
};

// The tile's heights: the header range and each vertex's code.
struct Quantized {
    double min_h = 0, max_h = 0, step = 0;
    int divisor = k_quantized_max; // the header range in steps
    std::vector<std::uint16_t> codes;
    std::uint16_t code(double h) const {
        const double c = std::round((h - min_h) / step) * double(k_quantized_max / divisor);
        return std::uint16_t(std::clamp(c, 0.0, double(k_quantized_max)));
    }
};

// The measure: every covered post inside the tile against the quantized TIN, by rows of posts
// under each triangle, twice: vertically, and as CesiumJS draws the triangle, flat between its
// vertices' Earth-centred positions (the post's distance to the drawn point at its place in the
// triangle, on the drawn surface: so at least its distance to that surface). Counts the triangles
// that rounding turned over (not counter-clockwise).
struct Measure {
    double max_error = 0.0; // vertical
    double max_drawn = 0.0;
    std::int64_t samples = 0;
    std::int64_t flipped = 0;
    std::int64_t missed = 0;   // covered posts inside the tile under no triangle
    std::int64_t inserted = 0; // posts the repair made vertices
};
// One triangle's posts: the largest of each error, and the worst post over the bound that the
// repair can make a vertex (its u/v strictly inside the tile and on none of the triangle's
// vertices), with its error (the larger of both), or 0.
struct TriangleError {
    double error = 0.0, drawn = 0.0, over = 0.0;
    std::int64_t i = 0, j = 0;
};

// Which way a thread's next pass over a tile's bands runs (tile_build.cpp).
bool next_pass_southward();

// The offset of lattice line `i` from an edge line at `edge` degrees, in u/v units of level z
// (tile_build.cpp).
double offset_units(double origin, double step, std::int64_t i, double edge, int z);

// Measures the triangles numbered in `which` (all of them when it is empty, and then also the
// samples, the posts under no triangle and the triangles turned over) into `errors`.
Measure measure(const GeoLattice &g, const TileId &id, const std::vector<Vertex> &vs,
                const Quantized &q, const std::vector<std::uint32_t> &triangles,
                const std::vector<std::uint32_t> &which, double bound,
                std::vector<TriangleError> &errors);

// Makes the posts over the bound vertices, then measures again the triangles that changed
// (tile_measure.cpp says how). Returns the measure of the repaired tile.
Measure repair(const GeoLattice &g, const TileId &id, double bound, Assembly &a, Quantized &q,
               std::vector<TriangleError> &errors, Measure m);

} // namespace tinlod::tiles
