// After the flip pass at a vertical bound on a DEM: a node's height need not be its sample's, only
// every sample within the bound of the TIN over it. Each interior node still standing is tried
// again, its hole triangulated (the min-max triangulation at the heights it has), with its ring's
// interior nodes free to move: a small linear programme says whether heights exist that keep
// every sample of the new triangles and of every triangle around a moved node within the limit.
// The outline's nodes keep their heights (a neighbouring tile meets them). The nodes near an erase
// are tried again, until none goes (docs/decisions/034-free-heights.md).
#pragma once

#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace tinlod::erase {

struct FreeHeightsStats {
    std::int64_t erased = 0; // nodes erased by the pass
    std::int64_t moved = 0;  // ring nodes whose height an erase changed (counted per erase)
};

// The pass on `tin` (a TIN over hf's samples, origin = sample id, as erase_dem returns it), each
// sample within `limit` (vertically) of the triangle over it, checked exactly at the heights
// written (floats). Returns the TIN it leaves (the nodes left in tin's order, origin = sample id,
// xy unchanged), and its counts in `stats` when given. Runs last: the flip pass and the erase
// take a node's height to be its sample's.
Mesh free_heights(const Mesh &tin, const Heightfield &hf, double limit, int max_valence,
                  FreeHeightsStats *stats = nullptr);

// chebyshev_fit's scratch, kept from call to call (a fresh tableau each call cost as much as the
// method).
struct FitScratch {
    std::vector<double> tableau, cost, reduced;
    std::vector<std::size_t> basis;
};

// The least L-infinity fit: z (n values) minimising max_i |a_i . z - b_i| over the rows a_i
// (row-major, a.size() == n * b.size()), by the simplex method on its dual (n + 1 equality rows).
// Returns that maximum at the z it leaves in `z`; stops early with a value over `give_up` once the
// optimum is known to exceed it, and returns +inf when the method does not settle.
double chebyshev_fit(int n, std::span<const double> a, std::span<const double> b, double give_up,
                     std::vector<double> &z, FitScratch &scratch);

} // namespace tinlod::erase
