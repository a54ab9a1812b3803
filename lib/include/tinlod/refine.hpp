// The refiner: one TIN that follows a moving observer both ways, frame after frame. Where the
// paper re-reads and rebuilds when the observer approaches (erased nodes "can not be accurately
// replaced"), the refiner keeps the record of every erase and brings nodes back exactly (Hoppe's
// view-dependent progressive meshes; De Floriani and Puppo's multi-triangulation), so each frame
// costs what changed, with the screen-space bound checked on every frame.
//
// A frame, Refiner::update(view) (lib/src/refine/update.cpp), with the thresholds derived from tau
// (RefineOptions::tolerance) and h (hysteresis): recover above tau, erase below (1 - h) tau. The
// files named are under lib/src/refine:
//
//   new view: the weigher, and how far the eye moved and the axis turned since each kept view
//   recover, top down (the recoveries a frame makes are chosen here):
//       work = the faces whose swallowed nodes may exceed tau
//              (the cells' and the live nodes' fan bounds clear the rest unwalked: fan_bounds.hpp)
//       while work is not empty: f = pop(work)
//           u = f's worst swallowed node over tau, if any          (face_check.hpp)
//           x = ready_dependency(u): the erase u's recovery waits on that can be undone now
//           reinsert(x); mark x and its ring dirty; push x's faces and f
//   erase:
//       candidates = the dirty live nodes, and those whose cost may have fallen to (1 - h) tau:
//                    their star's deviation times its weight now (a lower bound of the cost) is
//                    not over it; bounds carried from earlier views settle the rest unweighed
//                    (motion_bounds.hpp)
//       sweep_dirty(candidates, (1 - h) tau): the candidates, then the rings their erases changed
//
// Afterwards every swallowed node's weighted deviation is <= tau. A frame costs a few operations
// per live node in the cells the grid cannot clear (update_grid.hpp), plus the nodes that change.
#pragma once

#include "tinlod/decimate.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <cstdint>
#include <memory>

namespace tinlod {

class NodeSource;

namespace refine {
struct RefinerState; // the refiner's state (lib/src/refine/refiner.cpp)
}

struct RefineOptions {
    double tolerance = 1.0;   // tau: screen-space error every frame may show, pixels
    double hysteresis = 0.25; // erase only down to (1 - hysteresis) * tau, recover above tau, so a
                              // node near the threshold does not flicker; in [0, 1)
    // SP model: screen or paper (the refiner follows a view; Error for the vertical model)
    SpModel model = SpModel::screen;
    SignificanceOptions significance; // its parameters
    int max_valence = 24;             // nodes with more neighbours stay (bounds a hole's size)
    // From a Heightfield with the screen model: the first frame retrieves the quad-tree's TIN at
    // retrieve_share times the erase tolerance, (1 - hysteresis) tau, and erases from there. The
    // samples the retrieval left out enter later by local edits, where the observer comes close
    // (each has an erase record from the start). 0: the first frame erases from the full grid.
    double retrieve_share = 0.5;
};

struct FrameStats {
    std::int64_t nodes = 0;     // live nodes after the update
    std::int64_t triangles = 0; // live triangles after the update
    // What the update did. The first frame's: the initial erase and its update together (erased
    // counts both, recovered the update's, candidates the erase's evaluations, weights_ms the
    // eraser's construction, erase_ms the erase and the update; the other counts stay 0).
    UpdateStats update;
    double retrieve_ms = 0.0; // the first frame: quad-tree build and retrieval
    double total_ms = 0.0;
    // The first frame's erase bound: max weighted deviation of every erased node (pixels inside
    // the frustum, relaxed outside), <= tolerance. update() leaves it 0: it keeps every deviation
    // within tolerance without measuring the largest (measure_error does, over every sample).
    double bound_px = 0.0;
};

// Holds the current TIN and its erase history between frames.
class Refiner {
  public:
    // Starts from the grid TIN of `hf` seen from `first`: the quad-tree retrieval, then the erase
    // (see RefineOptions::retrieve_share), then one update from `first` that makes the bounds the
    // updates carry over. `hf` must outlive the refiner.
    Refiner(const Heightfield &hf, const View &first, const RefineOptions &options = {});
    // The same, the first retrieval read from `tree`, a quad-tree of hf's grid (a store, whose
    // bounds are on disk already: no quad-tree is built over hf), dropped once it has.
    Refiner(const Heightfield &hf, std::unique_ptr<NodeSource> tree, const View &first,
            const RefineOptions &options = {});
    // Starts from a mesh (a TIN or a surface mesh).
    Refiner(Mesh mesh, const View &first, const RefineOptions &options = {});
    ~Refiner();
    Refiner(const Refiner &) = delete;
    Refiner &operator=(const Refiner &) = delete;

    // The first frame's statistics (the initial erase and its update).
    const FrameStats &first_frame() const;
    // Moves to `view`: recovers where the bound would break, erases where SP fell below
    // (1 - hysteresis) tau. Afterwards every frame-visible deviation is <= tau pixels.
    FrameStats update(const View &view);

    // The current TIN: erased nodes and their faces are marked deleted, not removed. From a mesh,
    // vertex idx = input vertex. From a heightfield, a vertex per live sample (the origin property
    // names each): an erase frees its node's vertex for the next sample that enters or comes back,
    // so the TIN's memory follows its live nodes, not the grid or the samples ever live.
    const Mesh &mesh() const;
    bool is_erased(Mesh::VertexHandle v) const;
    // Bytes of the whole structure: the mesh's arrays and the erase history.
    std::size_t bytes() const;

  private:
    std::unique_ptr<refine::RefinerState> state_;
};

} // namespace tinlod
