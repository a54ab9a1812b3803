// The tuning constants of the erase and of the refiner's update, in one place: each says why it
// is what it is; the runs that chose it are in docs/decisions.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tinlod::erase {

// ---- Grid TINs: bands and tiles of the lattice scans (lattice_scan.hpp) ----

// A scan weighs a band of this many lattice rows at once (one weight bound per band).
inline constexpr std::int64_t k_band_rows = 16;
// A grid TIN's face over more than k_tiled_samples samples (a far flat, a slope seen from afar: on
// 4097² a face can hold millions) keeps a bound on its samples' deviation per tile of k_band_rows
// rows by k_tile_cols columns, made from each tile's height range without reading a sample, so a
// check weighs only the tiles whose bound can matter (docs/decisions/010-large-faces.md).
inline constexpr std::int64_t k_tile_cols = 64;
inline constexpr std::int64_t k_tiled_samples = 16384;
// A shallow history keeps what the fan faces of an erase knew of their samples (KeptFan) when they
// held more than this many in all: a re-insert then scans none of them (face_worst; 010).
inline constexpr std::int64_t k_kept_fan_samples = k_tiled_samples;

// ---- The erase's cost (erase_cost.cpp) ----

// How far past the limit evaluate's scan of a grid TIN's hole measures the cost: a cost barely
// over the limit fell back under it at the next frame's motion, and the node was scanned again
// frame after frame (docs/decisions/012-scan-reach.md).
inline constexpr double k_scan_reach = 2.0;

// ---- Sweeps and rungs (sweep.cpp) ----

// A mesh with swallowed lists sweeps once at tau / k_tau_rung_ratio before the passes at tau, so
// cheap erases go first; a grid TIN's one-off erase does not, where it only added time
// (docs/decisions/013-sweep.md).
inline constexpr double k_tau_rung_ratio = 8.0;
// A refiner's history (shallow) climbs from tau / k_history_rung_floor in rungs
// k_history_rung_ratio apart, so that its erases come in about the order of their costs, the
// order in which an observer who comes closer needs them back
// (docs/decisions/001-first-erase-rungs.md).
inline constexpr double k_history_rung_ratio = 1.1;
inline constexpr double k_history_rung_floor = 64.0;
// A node budget: the coarse rungs' limits grow by k_budget_rung_ratio, one pass each, until
// k_coarse_share times the budget remains; then the fine rungs, k_fine_rung_ratio apart, each
// swept until it erases nothing (docs/decisions/014-budget-rungs.md).
inline constexpr double k_budget_rung_ratio = 2.0;
inline constexpr std::int64_t k_coarse_share = 2;
inline constexpr double k_fine_rung_ratio = 1.05;
// The first coarse rung comes from the first costs of every k_sample_stride-th node (014).
inline constexpr std::uint32_t k_sample_stride = 29;
// A node whose ring changed in the pass under way is not erased in it while its fan swallowed
// more nodes than this many mean shares of a live node (input nodes over live nodes at the pass's
// start; see sweep_node): else a run of erases along a flat row drags one growing face from erase
// to erase. Relative, not fixed, as a retrieval's faces start large
// (docs/decisions/015-chain-and-update-caps.md; k_update_cap in decimate.hpp is the update's).
inline constexpr double k_chain_swallowed = 32.0;

// ---- The refiner's update (lib/src/refine) ----

// Live nodes per cell of the update's grid: the grid follows the live nodes, not the input, so
// its passes over the cells cost less than the walks over the nodes
// (docs/decisions/016-update-grid.md).
inline constexpr double k_live_per_cell = 64.0;
// The grid is sized again once the live nodes are this many times more, or fewer, than it was for.
inline constexpr std::int64_t k_regrid_ratio = 4;

// Lists at least this long get blocks when worst_swallowed scans them whole, so a later check
// skips the blocks that cannot matter (docs/decisions/010-large-faces.md).
inline constexpr std::size_t k_block_list = 256;
inline constexpr int k_block_side = 8; // blocks: a k_block_side² grid over the face's box in xy
inline constexpr std::size_t k_kept_scratch = 4096; // larger scratch is released after use

// The views of the last k_seen_views updates are kept for the bounds the updates carry over (see
// ViewBounds::face_seen_dev); an older bound is dropped.
inline constexpr std::uint32_t k_seen_views = 64;
// The update's walk over the nodes its bounds did not settle asks for their flags and their star's
// height this many nodes ahead: each is a cache miss (docs/decisions/009-prefetching.md).
inline constexpr std::size_t k_ahead = 8;

// ---- erase_dem (erase_dem.cpp) ----

// greedy_pays: the probe runs the insertion on k_probe_windows x k_probe_windows windows of the
// full-resolution samples, each 1 / k_probe_window_share of the grid's side (at least
// k_probe_window_min samples), spread over it; the insertion pays when it keeps at most
// k_probe_share + k_probe_margin of their samples: the windows' share is the whole grid's within
// 0.03 on the quick bench's inputs at 0.5-20 m, where a subsampled probe's was not (rough grids
// keep more at full resolution: docs/decisions/027-simplify-speed-3.md).
inline constexpr int k_probe_windows = 3;
inline constexpr int k_probe_window_share = 12;
inline constexpr int k_probe_window_min = 16;
inline constexpr double k_probe_margin = 0.02;
// Past this share of the samples the insertion to the end and the erase after it cost more than
// the erase from the grid for too few fewer triangles (docs/decisions/028-fewest-2.md, "After the
// merge"); once it runs, the insertion goes to DemEraseOptions::greedy_cap.
inline constexpr double k_probe_share = 0.72;

} // namespace tinlod::erase
