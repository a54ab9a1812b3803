// `simplify STORE` with a camera and a tolerance in memory bounded by the retrieved TIN and the
// store's tile cache, never the raster (issue #49; docs/decisions/031-bounded-store-erase.md): the
// quad-tree retrieval from the store's bounds, then an erase whose every candidate triangle is
// tested through the store's quad-tree, node boxes first and tile samples only where a box cannot
// pass whole, so no state is kept per sample.
#pragma once

#include "tinlod/decimate.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/store.hpp"
#include "tinlod/tin.hpp"

#include <glm/glm.hpp>

#include <string>

namespace tinlod {

// The screen model's TIN of `store` seen from model's view within `tolerance` (the weighted error
// of the node erase, deviation times the screen weight with its peripheral factor, at every
// sample): the retrieval at retrieve_share * tolerance (in (0, 1]), then nodes erased by
// half-edge collapses in rounds of rising thresholds (tolerance / 8, / 4, / 2, then tolerance
// until a round erases none), each collapse kept only when every sample under its new triangles
// is within the round's threshold. Not erase_dem's TIN (no cost order, no ring re-triangulation):
// fewer nodes on the views of decision 031. Its stats: first_stage quadtree, the retrieval's
// nodes and tolerance, and the erase's counts (erase.max_* are left 0: measure_store_error
// measures). Throws Error when the model is not the screen one or retrieve_share is outside (0, 1].
Mesh erase_store(TileStore &store, const Significance &model, double tolerance,
                 double retrieve_share, DemEraseStats *stats = nullptr);

// measure_error's max_vertical and max_screen_px (options.frustum_only as there) of a TIN made on
// the store's samples (origin property = sample id), tile by tile through the cache; samples,
// uncovered and rms_vertical are left 0 (they would need a flag per sample).
TinError measure_store_error(TileStore &store, const Mesh &tin, const ErrorOptions &options = {});

// check_eye_above for a store: Error naming `subject` when the eye is at or under grid_tin's
// surface.
void check_eye_above(TileStore &store, const glm::dvec3 &eye, const std::string &subject);

} // namespace tinlod
