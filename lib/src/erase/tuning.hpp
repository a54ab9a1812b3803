// The tuning constants of the erase and of the refiner's update, in one place: each says why it
// is what it is; the runs that chose it are in docs/decisions.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tinlod::erase {

// ---- Grid TINs: bands and tiles of the lattice scans (lattice_scan.hpp) ----

inline constexpr std::int64_t k_band_rows = 16;

// A grid TIN's face over more than k_tiled_samples samples (a far flat, a slope seen from afar:
// on 4097² a face can hold millions) keeps a bound on its samples' deviation per tile of the
// lattice's grid of k_band_rows rows by k_tile_cols columns, so that a check weighs only the tiles
// whose deviation can matter, where a band's bound must take the face's largest deviation. A low
// observer's frames on 4097² re-checked a few such faces of the far edge each, 5-30 ms apiece.
// The bounds come from each tile's height range (EraserState::tile_z) against the face's plane,
// with no sample read: a pass over every sample of a face that covers most of the terrain was most
// of the slowest frames of a descent from high above (36 of 57 ms, scratch runs on 4097²). A tile's
// scan then tightens its bound to its samples' largest deviation.
inline constexpr std::int64_t k_tile_cols = 64;
inline constexpr std::int64_t k_tiled_samples = 16384;
// A shallow history keeps what the fan faces of an erase knew of their samples (KeptFan) when they
// held more than this many in all: a re-insert then scans none of them (face_worst).
inline constexpr std::int64_t k_kept_fan_samples = k_tiled_samples;

// ---- The erase's cost (erase_cost.cpp) ----

// How far past the limit evaluate's scan of a grid TIN's hole measures the cost (see there). On
// the 4097² first flights at 30 frames per second (scratch runs, the same TINs): 12-22 % fewer
// candidates, the erase 4-23 % faster (paths' speed) and 12-19 % (a quarter of it); from 1.5 to
// the whole hole it made no difference.
inline constexpr double k_scan_reach = 2.0;

// ---- Sweeps and rungs (sweep.cpp) ----

// The sweep: passes over the nodes in index order (spatially coherent, so the half-edge arrays and
// the swallowed lists stay in cache, unlike a queue that jumps across the terrain), each erasing
// every node whose cost is within the pass's limit. A node is re-evaluated only when its ring
// changed or its last cost (a lower bound of the true one) is within the pass's limit. Measured on
// N42E001 (1.44 M nodes) from the demo view, against the queue alone in the same run:
//  - tolerance only: passes at tau until one erases nothing; 3.4-4x faster and 4 % fewer nodes at
//    tau = 1 px (42,087 against 43,897: the queue's strict order does not pay at a fixed bound).
//    Cheap erases may go first, in passes at lower limits (tau_rungs);
//  - node budget: the rungs' limits double while more than twice the budget remains (one pass
//    each), then rise by 5 % (fine_rungs) until the budget is met. A doubling rung used to repeat
//    its pass until one erased nothing: those repeats re-evaluate the nodes whose ring the last
//    pass changed, and the next rung, or the fine rungs (which start at the last doubling rung's
//    limit and sweep every dirty node), evaluate most of them again. One pass per rung: 19-21 %
//    fewer evaluations and 8-14 % less time at the benchmark's budgets (N42E001 low 673 k -> 546 k
//    evaluations, 1352 -> 1165 ms; high, top, Rainier and the 513² crop alike), every output
//    within 0.02 % of the same bound (scratch runs). The doubling rung that reaches twice the
//    budget may pass the bound the budget needs, and the budget is then met inside it: from above
//    (the benchmark's high and top views of N42E001 and Rainier) the output ends 23-26 % over the
//    bound an erase to a tolerance reaches with as many nodes. Rungs sized by the slope of the
//    last two (nodes against limit, in log-log, at least -1.5) got 1.03-1.07 px there instead of
//    1.23-1.24, for 5-15 % more time; doubling rungs down to 3 times the budget (k_coarse_share
//    3) got 1.04-1.07 px from every view for 11-27 % more evaluations (scratch runs): neither is
//    taken, as the low view's time is its margin on the 2 M input triangles/s goal. The first
//    rung is the first cost the budget makes unavoidable (see sweep_erase), not the 5th
//    percentile of the first costs: 2.1x faster on N42E001 to 35 k nodes (7.3 M evaluations to
//    2.4 M) at the same error.
//    The fine rungs replaced a queue over the last twice the budget (the least cost first, its
//    keys lower bounds refreshed at the top). Scratch runs at the benchmark's budgets, DEMs
//    through erase_dem: the erase takes 9-33 % less time (N42E001 low 1714 -> 1326 ms, high 1758
//    -> 1293, top 1642 -> 1146; Rainier low 1198 -> 868; N48W125 low 1619 -> 1117; the 513² crop
//    9-20 %) to a lower or equal bound (N42E001 low 1.097 -> 0.995 px, high 0.600 -> 0.573; the
//    513² crop 1.06-1.11 px against 1.14-1.17; Rainier low 1.131 -> 1.068, high and top and
//    N48W125 within 0.05 %). The queue's strict order does not pay at a budget either: the greedy
//    least cost first is not the least bound. The bunny to 2,860 nodes: 1.85 -> 1.66 px at the
//    same time; N42E001 in the vertical model to 40,193 nodes: 58.8 -> 52.5 m, 8 % faster.
//    Starting the fine rungs at the cut coarse rung's limit, not 5 % above it, matters: the part
//    of the terrain that rung had not swept got 5 % more error (Rainier high 1.26 -> 1.32 px).
//    The queue stays for the paper model, whose key is not a cost, and for an erase with no bound.
inline constexpr double k_tau_rung_ratio = 8.0;
// The passes at tau / ratio^k, k = tau_rungs(s) .. 1, before those at tau. A grid TIN's one-off
// erase has none: on N42E001 and Rainier, at tau = 1 px from the benchmark's views and at 1, 5, 10
// and 20 m in the vertical model, they cost 16-24 % more time for -1 % to +0.7 % nodes. A mesh
// with swallowed lists has one (the bunny at 0.5-4 px: none took 2 % more nodes, two 11-16 % more
// time for the same nodes).
// A refiner's history (shallow) climbs from tau / 64 in rungs 10 % apart, so that its erases come
// in about the order of their costs. An observer who comes closer needs the erased nodes back
// from the most costly down; within a rung a pass erases in storage order, and where a cheap
// node's erase came after a costly neighbour's and consumed its triangles, the costly node's
// recovery first brings the cheap one back, which the same update erases again. With two rungs
// 8 times apart, the 4097² flights at 30 frames per second changed 464-1,307 nodes per frame
// (medians), 35-38 % of the recoveries erased again by the same update; with rungs 10 % apart,
// 231-658 and 14-21 %, with 13-14 % fewer nodes. The first frame takes 1.8-1.9 times as long
// (4.5-5.9 s -> 8.5-11.0 s): the dirty ring nodes of a rung's erases are evaluated again in the
// next rung, where two rungs evaluated them once for many erases (3.4 M evaluations instead of
// 1.4 M on the descent's first frame). Rungs 20 % apart: 9-17 % more changes than 10 %, a first
// frame 1.5 times the two rungs'; 50 % apart, half the gain; 5 % apart, 6 % fewer changes still
// on the descent for a first frame 1.3 times as long again. Rungs within each update's erase as
// well (the first flights' scratch driver): as many changes, twice the evaluations.
inline constexpr double k_history_rung_ratio = 1.1;
inline constexpr double k_history_rung_floor =
    64.0; // tau / 1024 instead: the same changes per frame

inline constexpr double k_budget_rung_ratio = 2.0;
inline constexpr std::int64_t k_coarse_share =
    2; // the fine rungs erase from this many times the budget
inline constexpr double k_fine_rung_ratio = 1.05;
// A node whose ring changed in the pass under way is not erased in it while its fan swallowed
// more nodes than this many mean shares of a live node (input nodes over live nodes at the
// pass's start; see sweep_node). A fixed 32 nodes cut the runs short once a retrieval had made
// the faces large: relative, the erase takes 11-25 % less time to 3-8 % fewer nodes at tau = 1
// px from the benchmark's low and high views (N42E001, N48W125), 8-22 % less with a node budget
// at the same or lower error, and the full grids, whose shares start at 1, are unchanged.
inline constexpr double k_chain_swallowed = 32.0;
// k_update_cap (decimate.hpp): three flight paths on 4097², 20 updates each, with swallowed lists:
// 65,536 -> 4,096 took 19 % off the update time for 1.0-2.6 % more TIN nodes; 1,024 took 35 % off
// for 4-16 % more nodes. With the lattice scan of a grid TIN: 16,384 costs 6 % more time than 4,096
// for 0.9-2.2 % fewer nodes.
// Node budget: the sample of first costs. Every 29th node places the first rung as well as every
// 7th did (the same output on Rainier, within 1 % on N42E001), with 3-5 % fewer evaluations.
inline constexpr std::uint32_t k_sample_stride = 29;

// ---- The refiner's update (lib/src/refine) ----

// Live nodes per cell of the update's grid. The grid follows the live nodes, not the input: each
// update passes twice over the cells, and with cells of 1024 input nodes (16 k cells for the 43 k
// live nodes of a 4097² flight) those passes cost as much as the walks over the nodes. At 30 frames
// per second with the camera 8 times slower than the flight benchmark's paths, a frame's median
// took 19-24 % less with 64 live nodes per cell than with 1024 input nodes (scratch runs on the
// fly-over: 20 to 1,400 live nodes per cell were within 13 % of each other, 80 to 1,400 within
// 5 %).
inline constexpr double k_live_per_cell = 64.0;
// The grid is sized again once the live nodes are this many times more, or fewer, than it was for.
inline constexpr std::int64_t k_regrid_ratio = 4;

// Lists at least this long get blocks when worst_swallowed scans them whole.
inline constexpr std::size_t k_block_list = 256;
inline constexpr int k_block_side = 8; // blocks: a k_block_side² grid over the face's box in xy
inline constexpr std::size_t k_kept_scratch = 4096; // larger scratch is released after use

// The views of the last k_seen_views updates are kept for the bounds the updates carry over (see
// EraserState::face_seen_dev); an older bound is dropped.
inline constexpr std::uint32_t k_seen_views = 64;
// The update's walk over the nodes its bounds did not settle asks for their flags and their star's
// height this many nodes ahead (see NodeEraser::update).
inline constexpr std::size_t k_ahead = 8;

// ---- erase_dem (erase_dem.cpp) ----

// greedy_pays: the probe runs the insertion on every k_probe_step-th sample of each row and
// column, and the insertion pays when it keeps at most k_probe_share of them.
inline constexpr int k_probe_step = 4;
inline constexpr double k_probe_share = 0.92;

} // namespace tinlod::erase
