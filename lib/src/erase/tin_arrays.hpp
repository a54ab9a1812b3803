// A TIN over the lattice as triangle arrays, for the passes after the erase (the flip pass, the
// free heights): cheaper to walk and rewrite in place than the half-edge mesh.
#pragma once

#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tinlod::erase {

// Corner k of triangle t is corner[3t + k] (counter-clockwise, -1 when t is free), the triangle
// across its edge k -> k + 1 across[3t + k] (-1 on the outline), per node one of its triangles
// (-1 once erased), its sample, height and whether it is on the outline.
struct TinArrays {
    std::vector<std::uint32_t> sample;  // node -> lattice sample
    std::vector<std::int32_t> col, row; // node -> its sample's column and row
    std::vector<double> z;              // node -> its height (the mesh's)
    std::vector<std::uint8_t> outline;  // node -> on the TIN's outline
    std::vector<std::int32_t> corner, across, fan;

    int index_of(std::int32_t t, std::int32_t node) const {
        return corner[3 * std::size_t(t)] == node       ? 0
               : corner[3 * std::size_t(t) + 1] == node ? 1
                                                        : 2;
    }
    std::int32_t at(std::int32_t t, int k) const {
        return corner[3 * std::size_t(t) + std::size_t(k)];
    }

    // v's ring (counter-clockwise), its star's triangles and in each the index of its ring edge;
    // false when v is erased, on the outline, or its ring passes max_ring nodes.
    bool star(std::int32_t v, int max_ring, std::vector<std::int32_t> &ring,
              std::vector<std::int32_t> &triangles, std::vector<int> &edge) const;
};

// `mesh` (a TIN over hf's samples, origin = sample id) as arrays.
TinArrays tin_arrays(const Mesh &mesh, const Heightfield &hf);

// Tries every node once in storage order (spatially coherent), then the nodes each success names,
// until none goes: try_node(v) returns the nodes to try again (empty when v stays).
template <class TryNode> void until_none_goes(std::size_t nodes, TryNode &&try_node) {
    std::vector<std::int32_t> work, next;
    work.reserve(nodes);
    for (std::size_t v = 0; v < nodes; ++v)
        work.push_back(std::int32_t(v));
    std::vector<std::uint8_t> queued(nodes, 1);
    while (!work.empty()) {
        for (const std::int32_t v : work) {
            queued[std::size_t(v)] = 0;
            for (const std::int32_t x : try_node(v))
                if (!queued[std::size_t(x)]) {
                    queued[std::size_t(x)] = 1;
                    next.push_back(x);
                }
        }
        work.swap(next);
        next.clear();
    }
}

// The nodes left in their order (the sample order erase_dem promises), at their heights in `tin`,
// xy from `source` (the mesh tin_arrays read), origin = sample id; their triangles.
Mesh nodes_left(const TinArrays &tin, const Mesh &source);

} // namespace tinlod::erase
