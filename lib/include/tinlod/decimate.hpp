// Distance decay of a TIN by node erase (paper steps 3-5): the least significant node is erased
// and the hole it leaves is re-triangulated locally by ear clipping in a projection plane, with
// an error bound over the whole output and an exact, invertible record of every erase.
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
// swallow, is computed in lib/src/erase/erase_cost.cpp (evaluate). An
// erase is made only when every new triangle keeps all the nodes it covers within `tolerance`, so
// the output's error over every input node is <= tolerance: in pixels inside the view frustum, and
// relaxed by 1 / peripheral outside it.
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

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace tinlod {

class QuadTree;

namespace erase {
struct EraserState; // the eraser's state (lib/src/erase/state.hpp)
}

// ---- Hole re-triangulation in the projection plane (paper steps 3-4) --------------------------

// One triangle of a re-triangulated ring: three ring indices, counter-clockwise.
struct RingTriangle {
    std::uint8_t a, b, c;
};

enum class RingOrientation { ccw, cw, degenerate };

// Orientation of the closed polygon `ring` by the sign of its area.
RingOrientation ring_orientation(std::span<const glm::dvec2> ring);

// Paper step 3: the neighbours of a node ordered into a counter-clockwise ring around `centre`
// (by angle, starting from the negative x axis). Returns indices into `neighbours`.
std::vector<int> order_ring(const glm::dvec2 &centre, std::span<const glm::dvec2> neighbours);

// The paper's erasing-ability test for the ear at ring index i of the counter-clockwise polygon
// `ring`: the corner (i-1, i, i+1) is strictly convex and no other ring node lies in the closed
// triangle.
bool is_erasable_ear(std::span<const glm::dvec2> ring, int i);

// Ear clipping of a simple counter-clockwise polygon (at most k_max_ring nodes): among the erasable
// ears it clips the one whose circumcircle holds no other remaining node (a Delaunay ear), then the
// best shaped (2*sqrt(3)*area2 / sum of squared edges). Returns ring.size() - 2 triangles, or an
// empty vector when the ring cannot be triangulated without a fold-over.
std::vector<RingTriangle> triangulate_ring(std::span<const glm::dvec2> ring);

inline constexpr int k_max_ring = 48;

// ---- The node-erase decimater ------------------------------------------------------------------

enum class Projection { automatic, xy, mean_plane };

struct EraseOptions {
    // tau: pixels (screen, paper models) or world units (vertical); may be +inf, 0 erases only
    // nodes that lie exactly on their neighbours' surface
    double tolerance = 1.0;
    std::int64_t max_nodes = 0;       // stop once this many live nodes remain (0: no budget)
    SignificanceOptions significance; // SP model and its parameters
    Projection projection = Projection::automatic; // automatic: xy when every face is CCW in xy
    bool erase_boundary = true; // TINs: erase boundary nodes lying exactly on the outline's line
    int max_valence = 24;       // nodes with more neighbours stay (bounds the hole size)
    // Erase in passes of independent nodes (no two erased in one pass share a triangle), so every
    // chain of recover dependencies is at most as long as the passes: for a history that will be
    // recovered from (the refiner). Otherwise a pass may erase a node right after its neighbour,
    // which gives fewer nodes, faster, but chains along a row that a recover must undo whole.
    bool shallow_history = false;
    // A grid TIN holding only some of its lattice's samples (to_lattice_mesh): give the samples
    // it left out erase records, as if the erases had taken them from the whole grid in the
    // quad-tree's order (absent_sample_rings), so recover() and update() bring them in by local
    // edits like any erased node. A record is kept only where the ring is not the lattice's
    // regular one (RegularRings: none on a 2^k + 1 grid, about half of 1201 x 1201), 20-24
    // bytes each. Otherwise they never enter.
    bool absent_history = false;
    // With absent_history: the TIN is a quad-tree retrieval's (to_lattice_mesh of retrieve). On a
    // square 2^k + 1 grid every ring of a sample it left out is then the regular one (each leaf's
    // fan holds its centre, and each sample enters on the edge RegularRings names), so the
    // constructor takes them from the lattice without replaying the insertions, which took a third
    // of the refiner's first frame and 32 bytes per sample while they ran
    // (docs/decisions/019-erase-dem-first-stage.md). Other sizes replay as without it.
    bool retrieval_tin = false;
    // A sparse grid TIN: the mesh's vertices are some of this lattice's samples (the origin
    // property names each, its point as grid_vertices has it), triangulated over the lattice's
    // whole rectangle; the samples it left out have no vertex (as with to_lattice_mesh, see
    // absent_history) until they enter. An erase frees its node's vertex, and a sample that enters
    // or comes back takes a freed one (or a new one when none is free), so the mesh's memory
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

// What one NodeEraser::update did.
struct UpdateStats {
    std::int64_t recovered = 0;   // nodes re-inserted (dependency closures included)
    std::int64_t entered = 0;     // of those, samples the input TIN left out, there for the first
                                  // time (EraseOptions::absent_history)
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

// An update (NodeEraser::update) does not erase a node whose fan covers more input nodes than
// this: such an erase visits thousands of nodes to save one (on 4097² a face over a flat holds
// millions).
inline constexpr std::size_t k_update_cap = 4096;

// The history of the erases made on a TIN (or surface mesh): erase by significance, recover any
// erased node exactly. The eraser edits the caller's mesh in place (OpenMesh meshes cannot be
// moved, only copied); the mesh must outlive it. Vertex handles stay valid for the eraser's whole
// life: erased vertices, edges and faces are marked deleted and re-used on recover (compact()
// drops the erased edges and faces). Call mesh.garbage_collection() only once the eraser is gone.
class NodeEraser {
  public:
    // `mesh`: triangles only, no deleted elements, status attributes (tinlod::Mesh has them).
    // `view` may be null only for SpModel::vertical; it is copied. Throws Error naming the option
    // for a tolerance < 0 or NaN, max_nodes < 0, max_valence outside [3, k_max_ring], or a screen
    // or paper model without a view (set_view too).
    NodeEraser(Mesh &mesh, const View *view, const EraseOptions &options);
    ~NodeEraser();
    NodeEraser(NodeEraser &&) noexcept;
    NodeEraser &operator=(NodeEraser &&) noexcept;

    // classify -> rank -> erase -> retriangulate over every live node, until no node can be erased
    // within options.tolerance or options.max_nodes live nodes remain.
    EraseStats erase();

    // Re-inserts erased node v at its original position with its original triangles, first
    // recovering (recursively) any erased ring node it depends on. Returns the number of nodes
    // recovered (0 when v is live).
    std::int64_t recover(Mesh::VertexHandle v);
    // Recovers every erased node; the mesh then has the input's nodes and triangles.
    std::int64_t recover_all();

    // A new view (and model/tolerance) for the next erase(); node weights are recomputed as they
    // are needed.
    void set_view(const View *view, const EraseOptions &options);

    // Follows the observer to `view` in both directions (the refiner's frame step):
    //  1. recover: every face whose swallowed nodes exceed `recover_above` (weighted, the units of
    //     the tolerance) under the new weights gets nodes back top down, until every face is
    //     within `recover_above`: the erase its worst node's recovery waits on (the first erased
    //     ring node down the chain of dependencies, or the node itself) is undone, and the face is
    //     checked again. Faces are found from the live nodes' bounds on their fans (reach and
    //     largest deviation), so only the fans those bounds cannot clear are walked;
    //  2. erase: the nodes just recovered, the nodes whose ring changed, and the live nodes whose
    //     last evaluation's worst node (its deviation times its weight now: a lower bound of the
    //     cost) no longer keeps them above `erase_below` are swept (passes over those nodes and
    //     the rings their erases change) and erased while their cost stays <= `erase_below`.
    // Its cost follows the live nodes (a few operations each) and the nodes that change, not the
    // input's size.
    // With erase_below < recover_above a node between the two keeps its state (hysteresis). After
    // the call the whole-output bound holds at `recover_above`: every swallowed node's weighted
    // deviation is <= recover_above. Needs a view (not SpModel::vertical). Throws std::logic_error
    // for a TIN with samples left out but no EraseOptions::absent_history: they could not enter.
    UpdateStats update(const View &view, double recover_above, double erase_below);

    // Drops the erased edges and faces from the mesh's arrays (an erase from a grid keeps a few
    // percent of them): edge and face handles change, vertex handles stay (erased vertices remain,
    // marked deleted: they name the history), except with EraseOptions::lattice, where the erased
    // vertices go too and the live ones move down in order. Re-inserts then add what they need.
    // OpenMesh keeps the arrays' capacity; to give the memory back, copy the mesh and rebind.
    void compact();
    // Continues on `mesh`, a copy of the eraser's current mesh, for a long run of updates: the
    // large arrays (the mesh's and the eraser's) are moved to huge pages where the kernel allows,
    // and the bounds the updates keep on the live nodes' fans are built now (else the first update
    // after an erase() builds them).
    void rebind(Mesh &mesh);

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
    std::unique_ptr<erase::EraserState> state_;
};

// One-off: erases nodes of `mesh` in place from `view` (null for SpModel::vertical), then removes
// the deleted elements (garbage collection; the origin property keeps each node's provenance).
EraseStats erase_nodes(Mesh &mesh, const View *view, const EraseOptions &options);

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
    // The vertical model with a bound (no budget): greedy insertion (greedy.hpp) to the bound
    // first, when a probe on a coarser lattice says it keeps few enough samples (about half or
    // less, where it is faster than the erase from the grid); should it still pass this share of
    // the samples, it stops and the erase starts from the full grid (0: always from the grid).
    double greedy_cap = 0.6;
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
Mesh erase_dem(const Heightfield &hf, const View *view, const EraseOptions &options,
               const DemEraseOptions &dem = {}, DemEraseStats *stats = nullptr);

} // namespace tinlod
