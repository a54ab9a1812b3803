// The quad-tree of a Heightfield and its view-dependent retrieval: method 1 of the paper "Dynamic
// Data Retrieval and Distance Decay of TIN in Three Dimensional Visualizations" (elevations plus a
// node-status array, traversed from the root each frame), made crack-free as a restricted
// quad-tree (Röttger et al. 1998; Pajarola 1998) and sound with a conservative error bound per node
// (Lindstrom et al. 1996).
//
// Any size works without padding: the root covers the whole grid and every node splits its column
// and row ranges at their integer midpoints, so nodes are rectangles whose sides differ by at most
// one cell, and a range of one cell is not split (a node one cell wide splits in two, a 1x1 cell is
// terminal). Nodes of one level form a tensor grid, so neighbours share whole sides.
#pragma once

#include "tinlod/raster.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tinlod {

class Progress;

// One axis of the tree: the sample range [0, samples-1] split at integer midpoints level after
// level. Level d holds count(d) intervals; interval k spans samples lo(d, k) .. hi(d, k). Every
// axis of a tree has the same number of levels (the shallower one repeats its one-cell intervals),
// and the last level holds only one-cell intervals.
class AxisSplit {
  public:
    AxisSplit() = default;
    AxisSplit(int samples, int levels);
    // Levels needed to split `samples` samples down to one-cell intervals.
    static int levels_for(int samples);

    int levels() const { return static_cast<int>(starts_.size()); }
    std::uint32_t count(int d) const { return static_cast<std::uint32_t>(starts_[d].size() - 1); }
    std::uint32_t lo(int d, std::uint32_t k) const { return starts_[d][k]; }
    std::uint32_t hi(int d, std::uint32_t k) const { return starts_[d][k + 1]; }
    std::uint32_t length(int d, std::uint32_t k) const { return hi(d, k) - lo(d, k); }
    std::uint32_t parent(int d, std::uint32_t k) const { return parent_[d][k]; } // d >= 1
    std::uint32_t first_child(int d, std::uint32_t k) const { return first_child_[d][k]; }
    // Index k with lo(d, k) == s, or count(d) when s is the last sample; s must be such a bound.
    std::uint32_t bound_index(int d, std::uint32_t s) const;
    // Index k of the interval at level d with lo(d, k) <= s < hi(d, k); s < the last sample.
    std::uint32_t interval_of(int d, std::uint32_t s) const;

  private:
    std::vector<std::vector<std::uint32_t>> starts_;      // per level: count+1 interval bounds
    std::vector<std::vector<std::uint32_t>> parent_;      // per level: index of the parent interval
    std::vector<std::vector<std::uint32_t>> first_child_; // per level (but the last): first child
};

// The shape of a tree: its axes and its levels. Level 0 is the root; level levels()-1 holds only
// one-cell nodes. Node (d, i, j) spans columns x.lo(d,i)..x.hi(d,i) and rows y.lo(d,j)..y.hi(d,j).
struct QuadLayout {
    int width = 0;  // samples per row
    int height = 0; // rows
    AxisSplit x, y;

    QuadLayout() = default;
    QuadLayout(int width, int height);
    int levels() const { return x.levels(); }
    std::uint64_t level_nodes(int d) const { return std::uint64_t{x.count(d)} * y.count(d); }
    bool is_cell(int d, std::uint32_t i, std::uint32_t j) const {
        return x.length(d, i) == 1 && y.length(d, j) == 1;
    }
};

// Where the grid stands in the world (the Heightfield's frame without its elevations).
struct GridFrame {
    int width = 0;
    int height = 0;
    double dx = 1.0;       // ground spacing east, world units
    double dy = 1.0;       // ground spacing north, world units
    double origin_x = 0.0; // CRS coordinates of sample (0, 0)
    double origin_y = 0.0;
    std::string crs;
};

// What each node carries to make the split decision sound.
struct NodeBound {
    float error = 0.0f; // bound on |z_sample - z_node| over every sample the node covers, for its
                        // triangulation with any subset of its side midpoints, and >= every
                        // descendant's bound; world units, rounded up to float
    float zmin = 0.0f;  // the node's bounding box in z (its xy box is its sample rectangle)
    float zmax = 0.0f;
};

// The paper's node status. `unread`: the traversal never reached the node this frame.
enum class NodeStatus : std::uint8_t { leaf = 0, subdivide = 1, unread = 2 };

// Where a traversal reads node bounds and elevations from: the in-memory QuadTree or a TileStore.
class NodeSource {
  public:
    virtual ~NodeSource() = default;
    virtual const QuadLayout &layout() const = 0;
    virtual const GridFrame &frame() const = 0;
    // Bound of a node at a level below levels()-1 (one-cell nodes are never asked).
    virtual NodeBound bound(int d, std::uint32_t i, std::uint32_t j) = 0;
    // Elevation of sample (c, r), a vertex of the leaf (d, i, j) just retrieved.
    virtual float vertex_z(int d, std::uint32_t i, std::uint32_t j, std::uint32_t c,
                           std::uint32_t r) = 0;
    // Bracket one retrieval (a store pins the tiles it reads in between).
    virtual void begin_retrieval() {}
    virtual void end_retrieval() {}
};

// The in-memory quad-tree: the elevations (row-major, row 0 south, as the Heightfield) and, per
// level but the last, every node's bound.
class QuadTree {
  public:
    // Builds the bounds in O(samples * levels). `progress` (optional) advances by samples per
    // level. Throws Error when the grid is smaller than 2x2 or larger than 2^31 samples.
    explicit QuadTree(const Heightfield &hf, Progress *progress = nullptr);
    // The same, taking hf's elevations over instead of copying them (1 GB on a 16385² grid).
    explicit QuadTree(Heightfield &&hf, Progress *progress = nullptr);

    const QuadLayout &layout() const { return layout_; }
    const GridFrame &frame() const { return frame_; }
    const std::vector<float> &elevations() const { return z_; }
    float elevation(std::uint32_t c, std::uint32_t r) const {
        return z_[std::size_t{r} * frame_.width + c];
    }
    // Node (d, i, j) for d < levels()-1.
    const NodeBound &bound(int d, std::uint32_t i, std::uint32_t j) const {
        return bounds_[d][std::size_t{j} * layout_.x.count(d) + i];
    }
    std::int64_t node_count() const; // nodes with a stored bound

  private:
    void build(const Heightfield &hf, Progress *progress); // the bounds, once z_ holds hf's

    QuadLayout layout_;
    GridFrame frame_;
    std::vector<float> z_;
    std::vector<std::vector<NodeBound>> bounds_; // per level but the last, row-major (j, i)
};

struct RetrieveOptions {
    // tau: the screen-space error the output may show, pixels (0: the full grid, +inf: the root's
    // two triangles); Error when negative or NaN
    double tolerance = 1.0;
    bool cull = false; // nodes wholly outside the view frustum are not split
    // With the screen model's options: a node splits when its bound times the largest weight over
    // its box (k over the distance, times the peripheral factor; significance.hpp) exceeds
    // tolerance, the weighted error the node erase bounds, which relaxes the screen bound outside
    // the view. Null: the screen bound everywhere.
    const SignificanceOptions *peripheral = nullptr;
};

// The compact TIN of one view.
struct Retrieval {
    std::vector<std::uint32_t> nodes; // sample ids (r * width + c) of the TIN's nodes, each once
    std::vector<float> z;             // elevation of each node, parallel to `nodes`
    std::vector<std::uint32_t> triangles; // 3 sample ids per triangle, counter-clockwise from above
    std::int64_t tree_nodes = 0;          // tree nodes the traversal reached (leaf or subdivided)
    std::int64_t leaves = 0;              // leaves of the retrieved tree
    std::int64_t forced = 0;              // splits made only to keep neighbours within one level
    double bound_px = 0.0; // the guaranteed screen error: max over unsplit, unculled leaves
                           // of bound * k / distance(eye, leaf box), pixels (with
                           // RetrieveOptions::peripheral, times the peripheral factor)
};

// A traversal with its state kept between views: the status of every node of the last view stays
// readable (for incremental refinement on top), and buffers are reused. Costs O(output) per view
// (status is reset only where the last view set it).
class QuadTreeLod {
  public:
    explicit QuadTreeLod(const QuadTree &tree);
    explicit QuadTreeLod(std::unique_ptr<NodeSource> source);
    explicit QuadTreeLod(NodeSource &source); // borrowed: it outlives the traversal
    ~QuadTreeLod();
    QuadTreeLod(const QuadTreeLod &) = delete;
    QuadTreeLod &operator=(const QuadTreeLod &) = delete;

    // Retrieves the restricted quad-tree TIN of `view`: a node splits when its bound seen from the
    // nearest point of its box exceeds options.tolerance. The result lives until the next call.
    const Retrieval &retrieve(const View &view, const RetrieveOptions &options = {});

    const QuadLayout &layout() const;
    const GridFrame &frame() const;
    // Status of node (d, i, j) after the last retrieve().
    NodeStatus status(int d, std::uint32_t i, std::uint32_t j) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// One-off retrieval from an in-memory tree.
Retrieval retrieve(const QuadTree &tree, const View &view, const RetrieveOptions &options = {});

// The OpenMesh TIN of a retrieval (origin property = sample id, vertices in `nodes` order).
Mesh to_mesh(const Retrieval &retrieval, const GridFrame &frame);

// The retrieval's TIN on the whole lattice of `hf`, the grid it was retrieved from: vertex
// r * width + c for every sample (as grid_tin), the samples the retrieval left out deleted and
// isolated. A NodeEraser on it bounds every sample of the grid, retrieved or not.
Mesh to_lattice_mesh(const Retrieval &retrieval, const Heightfield &hf);
// The same TIN with only the retrieval's samples as vertices (origin property = sample id,
// vertices in sample order, points as grid_vertices has them), for a NodeEraser told the lattice
// (EraseOptions::lattice): its arrays follow the retrieval's nodes, not the grid's samples.
Mesh to_sparse_lattice_mesh(const Retrieval &retrieval, const Heightfield &hf);

} // namespace tinlod
