// The posts a tile's height range is made of (tiles.hpp: tile_height_range), before the fill
// height joins it: a tile's is the union of its four children's (their posts, with the next
// beyond each edge, are the parent's), so the pyramid reads the lattice once for every level.
#pragma once

#include "tinlod/tiles.hpp"

#include <cmath>

namespace tinlod::tiles {

struct PostRange {
    double lo = INFINITY, hi = -INFINITY; // of the covered posts
    bool covered = false;                 // a post holds a DEM height
    bool fill = false; // a post is not covered, or lies beyond the lattice: the fill height joins
    void add(const PostRange &r) {
        lo = std::min(lo, r.lo), hi = std::max(hi, r.hi);
        covered = covered || r.covered, fill = fill || r.fill;
    }
};

// The posts inside the tile and the next beyond each edge.
PostRange tile_post_range(const GeoLattice &lattice, const TileId &tile);
// Whether those posts reach the lattice at all (a tile that does not reads nothing).
bool tile_meets_lattice(const GeoLattice &lattice, const TileId &tile);
HeightRange with_fill(const PostRange &r, const TileOptions &options);

} // namespace tinlod::tiles
