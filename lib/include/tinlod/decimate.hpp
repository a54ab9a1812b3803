// Distance decay of a TIN by node erase (paper steps 3-5): nodes are erased while their SP allows
// (cheapest first, in sweeps whose limit rises to the bound; least significant first in the paper
// model: NodeEraser::erase) and the hole each leaves is re-triangulated locally by ear clipping in
// a projection plane, with an error bound over the whole output and an exact, invertible record
// of every erase. The SP model and its view: Significance (significance.hpp).
//
// Paper: "Dynamic Data Retrieval and Distance Decay of TIN in Three Dimensional Visualizations"
// (ring ordering, orientation, the erasing-ability test of an ear). Inverse erase and its
// dependency rule follow Hoppe's view-dependent progressive meshes and De Floriani and Puppo's
// multi-triangulation.
//
// The bound. Every erased node stays attached to the face that covers it (in the projection
// plane), so a face's error is the largest weighted deviation of the nodes it has swallowed;
// deviation = vertical distance to the face (TINs) or distance to the face, the triangle itself
// (general meshes); weight = the screen weight (k / OD * peripheral, tinlod/screen_weight.hpp), or
// 1 in the vertical model. The SP of an erase, the largest weighted deviation its new triangles
// swallow, is computed in lib/src/erase/erase_cost.cpp (evaluate). An erase is made only when
// every new triangle keeps all the nodes it covers within `tolerance`, so the output's error over
// every input node is <= tolerance: in pixels inside the view frustum, and relaxed by
// 1 / peripheral outside it.
//
// Projection plane: xy for a TIN (every face counter-clockwise seen from above), the area-weighted
// mean plane of the node's fan for a general surface mesh; a node is erased only when its fan is
// star-shaped in that plane and every new triangle has positive area there (never a fold-over) and,
// for general meshes, no new edge already exists (never a non-manifold edge).
//
// Boundary: a TIN boundary node is erased only when it lies exactly on the straight line of its two
// boundary neighbours in xy, so the outline never moves (its height error is bounded like any
// other node's). Corners and every boundary node of a general mesh are locked.
#pragma once

#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace tinlod {

class QuadTree;
class NodeSource;

namespace erase {
struct EraserState;    // the eraser's state (lib/src/erase/state.hpp)
struct HistoryOptions; // what only the refiner sets
class Follower;        // the refiner's state that follows the erase's edits
struct EraserAccess;   // the refiner's and the internal tests' way in
} // namespace erase

// The largest ring a hole may have (EraseOptions::max_valence's upper limit).
inline constexpr int k_max_ring = 48;

// ---- The node-erase decimater ------------------------------------------------------------------

enum class Projection { automatic, xy, mean_plane };

struct EraseOptions {
    // tau: pixels (screen, paper models) or world units (vertical); may be +inf, 0 erases only
    // nodes that lie exactly on their neighbours' surface
    double tolerance = 1.0;
    std::int64_t max_nodes = 0; // stop once this many live nodes remain (0: no budget)
    Projection projection = Projection::automatic; // automatic: xy when every face is CCW in xy
    bool erase_boundary = true; // TINs: erase boundary nodes lying exactly on the outline's line
    int max_valence = 24;       // nodes with more neighbours stay (bounds the hole size)
    // A grid TIN at a screen (or paper) bound without a budget: when a hole's Delaunay ears exceed
    // the bound, try the fans from its ring nodes (docs/decisions/033-node-erase-vs-collapses.md).
    // false: the ears alone, as a budget and the refiner's frames have them.
    bool hole_fans = true;
    // A sparse grid TIN: the mesh's vertices are some of this lattice's samples (the origin
    // property names each, its point as grid_vertices has it), triangulated over the lattice's
    // whole rectangle; the samples it left out have no vertex (as with to_lattice_mesh) and stay
    // erased (only a refiner brings them in). An erase frees its node's vertex, and a sample that
    // comes back takes a freed one (or a new one when none is free), so the mesh's memory
    // follows the live nodes, not the lattice. A vertex handle given to recover, is_erased or ring
    // names the sample its origin property names (a deleted vertex: the last sample it held).
    // Must outlive the eraser.
    const Heightfield *lattice = nullptr;
    // Called now and then by erase() (screen and vertical models) with the share of its work done,
    // non-decreasing in [0, 1] (for a progress bar). With a budget: the erases made over those it
    // needs; with a bound alone: the first sweep over the nodes (most of the time) takes 0.9 of it,
    // each next one 0.9 of what is left.
    std::function<void(double)> progress;
};

struct EraseStats {
    std::int64_t input_nodes = 0; // live nodes before
    std::int64_t input_triangles = 0;
    std::int64_t output_nodes = 0; // live nodes after
    std::int64_t output_triangles = 0;
    std::int64_t erased = 0;      // erases made by this call
    std::int64_t evaluations = 0; // hole re-triangulations tried (erase cost)
    // the bound reached: max over swallowed nodes of deviation * weight (tolerance units)
    double max_weighted = 0.0;
    // max over swallowed nodes inside the frustum of deviation * k / OD (0 without a view)
    double max_screen_px = 0.0;
    double max_vertical = 0.0; // max deviation over all swallowed nodes, world units: vertical in
                               // a TIN, the distance to the covering triangle on a surface mesh
    double erase_ms = 0.0;     // wall time of the erase
};

// The ring of an erased node's last erase, enough to undo it exactly (counter-clockwise; for a
// boundary node the open chain r_0..r_m along which the new boundary edge r_m -> r_0 runs). The
// triangles the erase removed are the fan (node, r_i, r_i+1); the ones it created are the faces
// inside the ring, so they need not be stored: they are present exactly when every ring node is
// live.
struct ErasedNodeRing {
    std::vector<std::uint32_t> nodes; // vertex idx values (samples with EraseOptions::lattice)
    bool boundary = false;
};

// What one of the refiner's updates did (FrameStats::update, refine.hpp).
struct UpdateStats {
    std::int64_t recovered = 0;   // nodes re-inserted (dependency closures included)
    std::int64_t entered = 0;     // of those, samples the input TIN left out, there for the first
                                  // time (a retrieval's TIN left them out)
    std::int64_t fans_kept = 0;   // of those, nodes whose fan held many grid samples: its faces
                                  // took back what they knew of them at the erase, unscanned
    std::int64_t erased = 0;      // nodes erased
    std::int64_t reerased = 0;    // of those, nodes this update had recovered (a recovery another
                                  // node's waited on, undone once that node was back)
    std::int64_t candidates = 0;  // live nodes whose erase was re-evaluated
    std::int64_t evaluations = 0; // erases tried: the candidates, then the ring nodes of the erases
                                  // made (an erase that fails keeps its node)
    std::int64_t faces_checked = 0; // faces whose swallowed nodes were re-measured
    double weights_ms = 0.0;        // the new view's weigher (node weights follow on demand)
    double recover_ms = 0.0;        // the recover pass
    double erase_ms = 0.0;          // the erase pass
};

// A refiner's update (Refiner::update) does not erase a node whose fan covers more input nodes than
// this: such an erase visits thousands of nodes to save one (on 4097² a face over a flat holds
// millions).
inline constexpr std::size_t k_update_cap = 4096;

// The history of the erases made on a TIN (or surface mesh): erase by significance, recover any
// erased node exactly. The eraser edits the caller's mesh in place (OpenMesh meshes cannot be
// moved, only copied); the mesh must outlive it. Vertex handles stay valid for the eraser's whole
// life: erased vertices, edges and faces are marked deleted and re-used on recover. Call
// mesh.garbage_collection() only once the eraser is gone.
class NodeEraser {
  public:
    // `mesh`: triangles only, no deleted elements, status attributes (tinlod::Mesh has them).
    // `model`: the SP model and its view (copied). Throws Error naming the option for a tolerance
    // < 0 or NaN, max_nodes < 0 or max_valence outside [3, k_max_ring] (set_view too).
    NodeEraser(Mesh &mesh, const Significance &model, const EraseOptions &options);
    ~NodeEraser();
    NodeEraser(NodeEraser &&) noexcept;
    NodeEraser &operator=(NodeEraser &&) noexcept;

    // Erases live nodes until none can be erased within options.tolerance or options.max_nodes
    // live nodes remain (lib/src/erase/sweep.hpp). The screen and vertical models with a bound or
    // a budget sweep: passes over the nodes in storage order erase each node whose cost (the SP
    // of its erase) is within the pass's limit, the limits rising to tau (or, under a budget,
    // rung by rung until N nodes remain). The paper model (whose key is not a cost) and an
    // unbounded erase use a queue: rank every node by its key, pop the least while its erase
    // stays within tau.
    EraseStats erase();

    // Re-inserts erased node v at its original position with its original triangles, first
    // recovering (recursively) any erased ring node it depends on. Returns the number of nodes
    // recovered (0 when v is live).
    std::int64_t recover(Mesh::VertexHandle v);
    // Recovers every erased node; the mesh then has the input's nodes and triangles.
    std::int64_t recover_all();

    // A new model and view (and options) for the next erase(); node weights are recomputed as
    // they are needed.
    void set_view(const Significance &model, const EraseOptions &options);

    bool is_erased(Mesh::VertexHandle v) const;
    // The ring of erased node v's last erase.
    ErasedNodeRing ring(Mesh::VertexHandle v) const;

    // The current TIN, the caller's mesh: erased elements are marked deleted, not removed.
    const Mesh &mesh() const;
    std::int64_t live_nodes() const;
    std::int64_t live_triangles() const;
    // Error of the current TIN over every swallowed node (see EraseStats).
    EraseStats measure() const;
    // What erasing live node v would cost now: the largest weighted deviation, under the current
    // view, of the nodes its re-triangulated hole swallows (measured over all of them; +inf when v
    // is locked or its hole cannot be re-triangulated without a fold-over, a non-manifold edge or
    // a moved outline), and the input nodes its fan covers (by area, or on a grid TIN the samples
    // in its hole, the larger): an update leaves a node that covers more than k_update_cap as it
    // is until its ring changes. The TIN does not change. Tells why a node stays live.
    struct Cost {
        double cost = INFINITY;
        double covered = 0.0;
    };
    Cost erase_cost(Mesh::VertexHandle v);
    // Bytes held by the eraser beside the mesh: per-node state, records, rings, free lists.
    std::size_t history_bytes() const;

  private:
    friend struct erase::EraserAccess;
    // The refiner's: with the options only it sets, and its state that follows the edits (null:
    // none).
    NodeEraser(Mesh &mesh, const Significance &model, const EraseOptions &options,
               const erase::HistoryOptions &history, erase::Follower *follower);

    std::unique_ptr<erase::EraserState> state_;
};

// One-off: erases nodes of `mesh` in place under `model`, then removes the deleted elements
// (garbage collection; the origin property keeps each node's provenance).
EraseStats erase_nodes(Mesh &mesh, const Significance &model, const EraseOptions &options);

// ---- Both methods on a DEM ---------------------------------------------------------------------

// erase_dem throws Error naming the option for a share outside its range (retrieve_share and
// greedy_cap in [0, 1], budget_share finite and >= 0).
struct DemEraseOptions {
    // With a tolerance: the quad-tree retrieval keeps retrieve_share * tolerance, the erase the
    // rest of the budget (0: the erase starts from the full grid).
    double retrieve_share = 0.5;
    // With a node budget: the retrieval keeps about this many times the budget, at most half of the
    // samples (its tolerance is searched for, and kept <= retrieve_share * tolerance when both a
    // budget and a tolerance are given), the erase the rest; 0, or a budget over 2/3 / budget_share
    // of the samples (1/12 of them at 8: the retrieval would keep under 3/4 of its share): the full
    // grid.
    double budget_share = 8.0;
    const QuadTree *tree = nullptr; // the DEM's quad-tree when one is built already
    // Or its store (a TileStore of this DEM), whose bounds the retrieval reads instead of building
    // them; borrowed.
    NodeSource *nodes = nullptr;
    // The vertical model with a bound (no budget): greedy insertion (greedy.hpp) to the bound
    // first, when a probe on a coarser lattice says it keeps few enough samples (about half or
    // less, where it is faster than the erase from the grid); should it still pass this share of
    // the samples, it stops and the erase starts from the full grid (0: always from the grid).
    // All of them by default: an insertion the probe let through that ends keeps fewer triangles
    // than the grid's erase for about its time (docs/decisions/028-fewest-2.md).
    double greedy_cap = 1.0;
    // The vertical model with a bound (no budget): true keeps every node on its sample's height;
    // false lets the last pass move interior nodes' heights within the bound to erase more
    // (docs/decisions/034-free-heights.md).
    bool sample_heights = false;
    // The vertical model with a bound (no budget): true runs the flip pass after the erase (each
    // node left tried again with its hole widened by the triangle across one of its ring edges),
    // 0.4-3.1 % fewer triangles for 1.1-1.7 times the run; off by default
    // (docs/decisions/046-flip-pass-opt-in.md).
    bool flip_pass = false;
};

// What the erase of erase_dem started from.
enum class FirstStage { grid, quadtree, greedy };
inline const char *first_stage_name(FirstStage stage) {
    return stage == FirstStage::grid       ? "grid"
           : stage == FirstStage::quadtree ? "quadtree"
                                           : "greedy";
}

struct DemEraseStats {
    EraseStats erase;                 // the erase, on the retrieved TIN
    std::int64_t retrieved_nodes = 0; // the retrieval's nodes (the grid's when it was skipped)
    double retrieve_tol = 0.0;        // its tolerance, pixels or (greedy) metres (0: the full grid)
    double retrieve_ms = 0.0;         // quad-tree build or greedy insertion, retrieval and mesh
    FirstStage first_stage = FirstStage::grid;
};

// A DEM's TIN by both methods of the paper: the quad-tree retrieval (method 1) as a TIN on the
// whole lattice with vertices for its samples only (to_sparse_lattice_mesh, EraseOptions::lattice:
// the memory follows the retrieval, not the grid), then node erase (method 2) of its nodes, which
// measures every sample of the grid under a new triangle, retrieved or not: the bound holds for the
// whole grid exactly as an erase from the full grid. The retrieval does in one traversal what the
// erase would do node by node where the terrain is smooth. Only the screen model retrieves: the
// paper model's SP is not a screen error a retrieval could share, and for the vertical model the
// quad-tree's bounds (any subset of side midpoints) are too loose to spare the erase any work
// (docs/decisions/019-erase-dem-first-stage.md): it starts from greedy insertion instead, where
// that keeps few samples (DemEraseOptions::greedy_cap), and erases from there. The others erase
// from the full grid. Returns the TIN's live nodes and faces (live_copy: the nodes and triangles
// erase_nodes leaves, in sample order; origin = sample id).
Mesh erase_dem(const Heightfield &hf, const Significance &model, const EraseOptions &options,
               const DemEraseOptions &dem = {}, DemEraseStats *stats = nullptr);

} // namespace tinlod
