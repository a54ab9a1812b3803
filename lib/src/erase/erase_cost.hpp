// The SP of an erase (Hole::sp): the largest weighted deviation of the nodes the new triangles
// swallow (the node itself, the nodes its fan had swallowed, and on a grid TIN every sample in the
// hole), each deviation weighted by the node's screen weight under the view (significance.hpp's
// screen model, tinlod/screen_weight.hpp), or 1 in the vertical model. evaluate() re-triangulates
// a node's hole and computes it; an erase is made when it is within the tolerance, so the output's
// error over every input node is within it. The queue's key is derived from it (key_of); the paper
// model orders its queue by the paper's SP instead.
#pragma once

#include "erase/state.hpp"

#include <cstddef>
#include <limits>

namespace tinlod::erase {

// Weigher::bound times this bounds the stored weights too (rounded up to float).
constexpr double k_rounded_weight = 1.0 + 1e-6;

// Node `node`'s weight under the current view: the weigher at the node rounded up to a float,
// from ViewWeights::per_vertex when it is kept.
inline double weight_of(const EraserState &s, std::uint32_t node) {
    if (s.weights.unit_weights)
        return 1.0;
    if (!s.weights.per_vertex.empty())
        return double(s.weights.per_vertex[node]);
    return double(float_up(s.weights.weigher(to_glm(node_point(s, node)))));
}

// A swallowed node's term of the SP: its deviation times its weight.
inline double weighted(const EraserState &s, std::uint32_t node, double dev) {
    return dev > 0.0 ? dev * weight_of(s, node) : 0.0;
}

// The weights for a new view (s.weights.weigher): `keep` computes them for every vertex (erase),
// else they go (each is computed where it is needed).
void new_weights(EraserState &s, bool keep);

// classify: which nodes may ever be erased, and each node's weight.
void classify_nodes(EraserState &s);

// A bound of the stored weights of the nodes a TIN face with corners a, b, c swallowed, which lie
// in its corners' box in xy and within `maxdev` of it in z (with a margin for the float rounding
// of maxdev and of the deviations' recomputation).
inline double swallowed_weight_bound(const EraserState &s, const glm::dvec3 &a, const glm::dvec3 &b,
                                     const glm::dvec3 &c, float maxdev) {
    const glm::dvec3 dz(0.0, 0.0, 1.001 * double(maxdev));
    return s.weights.weigher.bound(glm::min(glm::min(a, b), c) - dz,
                                   glm::max(glm::max(a, b), c) + dz) *
           k_rounded_weight;
}

// The SP and its node after the samples of h.pending, as raising the SP sample by sample in
// scan order would leave them (the first node whose weighted deviation exceeds `limit`, else the
// first of the largest above the SP), weighing fewer of them: by their bound, largest first, once
// one exceeding the limit is ruled out. False when the SP exceeds `limit`. Empties h.pending.
bool raise_pending(const EraserState &s, Hole &h, double limit);

// Re-triangulates v's hole into s.scratch.hole and computes the erase's SP into s.scratch.hole.sp
// (exactly up to `limit`, beyond it only as some value > limit); false when v cannot be erased
// without a fold-over, a non-manifold edge or a moved outline. With more than `max_swallowed` nodes
// under the fan it stops and sets hole.deferred.
bool evaluate(EraserState &s, VH v, double limit,
              std::size_t max_swallowed = std::numeric_limits<std::size_t>::max());

// The queue key of the evaluated hole: its SP rounded to float, or the paper's SP in the paper
// model.
float key_of(const EraserState &s, const Hole &h);

} // namespace tinlod::erase
