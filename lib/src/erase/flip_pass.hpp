// After the erase converges at a vertical bound on a DEM: each node still standing is tried again,
// its hole widened by the triangle across one of its ring edges (the erase of the node after a
// flip of that edge towards it), and re-triangulated by the hole's min-max triangulation over the
// lattice's samples. The nodes whose rings an erase changed are tried again, until none goes
// (docs/decisions/026-fewer-at-fine-bounds.md).
#pragma once

#include "tinlod/decimate.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"

#include <cstdint>

namespace tinlod::erase {

struct FlipPassStats {
    std::int64_t erased = 0;  // nodes erased by the pass
    std::int64_t widened = 0; // of them, those whose hole took the triangle across a ring edge
};

// Whether erase_dem runs the pass: the vertical model with a positive finite bound and no budget
// (the erase's min-max hole's case: docs/decisions/023-fine-bounds.md).
bool flip_pass_applies(const Significance &model, const EraseOptions &options);

// The pass on `tin` (a TIN over hf's samples, origin = sample id, as erase_dem returns it), each
// sample within `limit` (vertically) of the triangle over it. Returns the TIN it leaves (the nodes
// left in tin's order, origin = sample id), and its counts in `stats` when given.
Mesh flip_pass(const Mesh &tin, const Heightfield &hf, double limit, int max_valence,
               FlipPassStats *stats = nullptr);

// Whether no triangle over three of n points (columns x, rows y relative to a sample, none at it;
// heights h) whose closed lattice triangle holds the sample has its plane within `stop` of height
// z there, a rounding margin over. Shown by a plane above every point (or below every one) more
// than that under (over) z at the sample: the simplex walk over the triangles that hold the sample
// from `start` (three indices whose closed triangle holds it, counter-clockwise), towards the
// lifted points' upper (lower) hull, until such a plane or a triangle within reach of z turns up.
// False when neither side rules the cover out (not a proof that some triangle covers). Leaves
// in `start` the walk's last triangle (it holds the sample too).
bool cover_ruled_out(const std::int64_t *x, const std::int64_t *y, const double *h, int n, double z,
                     double stop, int start[3]);

} // namespace tinlod::erase
