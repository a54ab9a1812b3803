// Node erase with local hole re-triangulation and exact recovery (decimate.hpp).
//
// Paper steps 3-5 of "Dynamic Data Retrieval and Distance Decay of TIN in Three Dimensional
// Visualizations": order the erased node's neighbours into a ring, find its orientation, clip ears
// that contain no other ring node. The erase is inverted as a vertex split in the manner of Hoppe's
// view-dependent progressive meshes, its dependencies following De Floriani and Puppo's
// multi-triangulation: an erase's triangles are present exactly when all of its ring is live.
//
// The half-edge structure is rewired in place through OpenMesh's inline kernel setters: a node of
// valence n frees 3 edges and 2 faces (a boundary node 2 and 1) and the remaining n-3 spoke edges
// and n-2 faces become the new diagonals and triangles. Freed elements are kept on free lists and
// re-used by recover, so no library-side OpenMesh call (and no garbage collection) runs per erase.
#include "tinlod/decimate.hpp"

#include "lattice_rings.hpp"
#include "lattice_triangle.hpp"
#include "tinlod/closest_point.hpp"
#include "tinlod/focal.hpp"
#include "tinlod/greedy.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/util.hpp"
#include "weigher.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <unordered_map>

namespace tinlod {

using VH = Mesh::VertexHandle;
using HH = Mesh::HalfedgeHandle;
using EH = Mesh::EdgeHandle;
using FH = Mesh::FaceHandle;

namespace {

// ---- 2-D predicates ----------------------------------------------------------------------------

double orient(const glm::dvec2 &a, const glm::dvec2 &b, const glm::dvec2 &c) {
    return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

bool in_closed_triangle(const glm::dvec2 &a, const glm::dvec2 &b, const glm::dvec2 &c,
                        const glm::dvec2 &p) {
    return orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0;
}

// Positive when d lies strictly inside the circumcircle of the counter-clockwise triangle abc.
double in_circle(const glm::dvec2 &a, const glm::dvec2 &b, const glm::dvec2 &c,
                 const glm::dvec2 &d) {
    const double adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y;
    const double cdx = c.x - d.x, cdy = c.y - d.y;
    return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) -
           (bdx * bdx + bdy * bdy) * (adx * cdy - cdx * ady) +
           (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}

// The paper's erasing-ability test of the ear (a, b, c) of the remaining polygon linked by `next`:
// strictly convex at b and no other remaining node in the closed triangle. Returns the ear's shape
// quality in (0, 1] (2*sqrt(3)*area2 / sum of squared edges), or -1 when it is not erasable.
double ear_quality(const glm::dvec2 *q, const std::uint8_t *next, int a, int b, int c) {
    const double area2 = orient(q[a], q[b], q[c]);
    if (area2 <= 0.0)
        return -1.0;
    for (int j = next[c]; j != a; j = next[j])
        if (in_closed_triangle(q[a], q[b], q[c], q[j]))
            return -1.0;
    const auto sq = [](const glm::dvec2 &v) { return v.x * v.x + v.y * v.y; };
    const double edges = sq(q[b] - q[a]) + sq(q[c] - q[b]) + sq(q[a] - q[c]);
    return 2.0 * std::sqrt(3.0) * area2 / edges;
}

// Whether the circumcircle of the ear (a, b, c) holds no other remaining node (a Delaunay ear).
bool is_delaunay_ear(const glm::dvec2 *q, const std::uint8_t *next, int a, int b, int c) {
    for (int j = next[c]; j != a; j = next[j])
        if (in_circle(q[a], q[b], q[c], q[j]) > 0.0)
            return false;
    return true;
}

// Ear clipping of the counter-clockwise polygon q[0..n); writes n-2 triangles to `out` and returns
// their count, or -1 when no erasable ear is left before the end. Each step clips the best shaped
// Delaunay ear, or the best shaped ear when none is Delaunay; the circumcircle test runs only on
// ears in order of quality until one passes (a Delaunay ear stays Delaunay as nodes leave).
int clip_ears(const glm::dvec2 *q, int n, RingTriangle *out) {
    if (n < 3 || n > k_max_ring)
        return -1;
    std::array<std::uint8_t, k_max_ring> prev, next;
    std::array<double, k_max_ring> quality;
    std::array<bool, k_max_ring> delaunay; // known to be a Delaunay ear
    for (int i = 0; i < n; ++i) {
        prev[i] = std::uint8_t((i + n - 1) % n);
        next[i] = std::uint8_t((i + 1) % n);
        delaunay[i] = false;
    }
    for (int i = 0; i < n; ++i)
        quality[i] = ear_quality(q, next.data(), prev[i], i, next[i]);
    int first = 0, count = 0;
    std::array<std::uint8_t, k_max_ring> order;
    for (int remaining = n; remaining > 3; --remaining) {
        int valid = 0;
        int i = first;
        do {
            if (quality[i] >= 0.0)
                order[valid++] = std::uint8_t(i);
            i = next[i];
        } while (i != first);
        if (valid == 0)
            return -1; // no erasable ear: the ring is not a simple ccw polygon in this plane
        for (int k = 1; k < valid; ++k) // insertion sort by quality, best first: a handful of ears
            for (int j = k; j > 0 && quality[order[j]] > quality[order[j - 1]]; --j)
                std::swap(order[j], order[j - 1]);
        int best = order[0];
        for (int k = 0; k < valid; ++k) {
            const int e = order[k];
            if (delaunay[e] || is_delaunay_ear(q, next.data(), prev[e], e, next[e])) {
                delaunay[e] = true;
                best = e;
                break;
            }
        }
        const int a = prev[best], c = next[best];
        out[count++] = {std::uint8_t(a), std::uint8_t(best), std::uint8_t(c)};
        next[a] = std::uint8_t(c);
        prev[c] = std::uint8_t(a);
        if (first == best)
            first = c;
        quality[a] = ear_quality(q, next.data(), prev[a], a, c);
        quality[c] = ear_quality(q, next.data(), a, c, next[c]);
        delaunay[a] = delaunay[c] = false;
    }
    const int a = first, b = next[a], c = next[b];
    if (orient(q[a], q[b], q[c]) <= 0.0)
        return -1;
    out[count++] = {std::uint8_t(a), std::uint8_t(b), std::uint8_t(c)};
    return count;
}

glm::dvec3 to_glm(const Mesh::Point &p) { return {p[0], p[1], p[2]}; }

// Indexed binary min-heap of nodes by key.
class NodeHeap {
  public:
    void reset(std::size_t nodes) {
        key_.assign(nodes, 0.0f);
        pos_.assign(nodes, -1);
        heap_.clear();
    }
    bool empty() const { return heap_.empty(); }
    bool contains(std::uint32_t v) const { return pos_[v] >= 0; }
    std::uint32_t top() const { return heap_.front(); }
    // Smallest key below the top (+inf when the top is alone).
    float second_key() const {
        float k = INFINITY;
        for (std::size_t c = 1; c < std::min<std::size_t>(3, heap_.size()); ++c)
            k = std::min(k, key_[heap_[c]]);
        return k;
    }
    // Builds the heap at once from the nodes whose key was stored with store_key.
    void build(std::vector<std::uint32_t> nodes) {
        heap_ = std::move(nodes);
        for (std::size_t i = 0; i < heap_.size(); ++i)
            pos_[heap_[i]] = std::int32_t(i);
        for (std::size_t i = heap_.size() / 2; i-- > 0;)
            down(std::int32_t(i));
    }
    float key(std::uint32_t v) const { return key_[v]; }
    bool has_key(std::uint32_t v) const { return v < key_.size(); }
    void store_key(std::uint32_t v, float key) { key_[v] = key; } // for a node outside the heap
    void set(std::uint32_t v, float key) {
        if (pos_[v] < 0) {
            key_[v] = key;
            pos_[v] = std::int32_t(heap_.size());
            heap_.push_back(v);
            up(pos_[v]);
            return;
        }
        const float old = key_[v];
        key_[v] = key;
        if (key < old)
            up(pos_[v]);
        else
            down(pos_[v]);
    }
    // Frees the queue, keeping every stored key (store_key and key work until the next reset).
    void release_queue() {
        std::vector<std::int32_t>().swap(pos_);
        std::vector<std::uint32_t>().swap(heap_);
    }
    // Frees the keys too (until the next reset).
    void release() {
        std::vector<float>().swap(key_);
        release_queue();
    }
    void pop() {
        const std::uint32_t v = heap_.front();
        pos_[v] = -1;
        const std::uint32_t last = heap_.back();
        heap_.pop_back();
        if (heap_.empty())
            return;
        heap_[0] = last;
        pos_[last] = 0;
        down(0);
    }
    std::size_t bytes() const {
        return key_.capacity() * 4 + pos_.capacity() * 4 + heap_.capacity() * 4;
    }

  private:
    void up(std::int32_t i) {
        const std::uint32_t v = heap_[i];
        while (i > 0) {
            const std::int32_t p = (i - 1) / 2;
            if (!(key_[v] < key_[heap_[p]]))
                break;
            heap_[i] = heap_[p];
            pos_[heap_[i]] = i;
            i = p;
        }
        heap_[i] = v;
        pos_[v] = i;
    }
    void down(std::int32_t i) {
        const std::uint32_t v = heap_[i];
        const std::int32_t n = std::int32_t(heap_.size());
        for (;;) {
            std::int32_t c = 2 * i + 1;
            if (c >= n)
                break;
            if (c + 1 < n && key_[heap_[c + 1]] < key_[heap_[c]])
                ++c;
            if (!(key_[heap_[c]] < key_[v]))
                break;
            heap_[i] = heap_[c];
            pos_[heap_[i]] = i;
            i = c;
        }
        heap_[i] = v;
        pos_[v] = i;
    }
    std::vector<float> key_;
    std::vector<std::int32_t> pos_;
    std::vector<std::uint32_t> heap_;
};

// A new triangle's barycentric weights and height as affine functions of the projected point.
struct TriangleFrame {
    glm::dvec3 w0, w1;  // weight of corners a and b: dot(w, (x, y, 1)); c gets the rest
    glm::dvec3 height;  // xy: z = dot(height, (x, y, 1))
    double slope = 0.0; // xy: |grad z|
};

// The hole a node leaves, projected and re-triangulated (scratch of one evaluation).
struct Hole {
    VH v;
    int n = 0; // ring nodes
    bool boundary = false;
    std::array<VH, k_max_ring> r;
    std::array<HH, k_max_ring> h; // spokes v -> r_i
    std::array<glm::dvec3, k_max_ring> p;
    std::array<glm::dvec2, k_max_ring> q; // projected ring
    std::array<RingTriangle, k_max_ring> tri;
    std::array<TriangleFrame, k_max_ring> frame;
    int ntri = 0;
    glm::dvec3 origin{0.0}, ex{1, 0, 0}, ey{0, 1, 0}; // projection frame (xy: the world frame)
    double delta = 0.0;     // the node's own deviation from the new triangles
    double cost = 0.0;      // max weighted deviation over the node and the fan's swallowed nodes
    std::uint32_t star = 0; // the node that gave the cost, and its (unweighted) deviation
    double star_dev = 0.0;
    bool deferred = false; // the fan swallowed more nodes than the evaluation may visit
    // A grid TIN's evaluation (see scan_lattice): per new triangle, the largest deviation of the
    // samples it swallows and the sample that has it (-1 when none deviates).
    std::array<float, k_max_ring> tri_maxdev;
    std::array<std::int32_t, k_max_ring> tri_worst;
    // A band's samples whose weighted deviation may raise the cost (see scan_hole), in scan order:
    // the sample, its deviation, that times the band's weight bound, and its weighted deviation
    // (-1 until computed).
    struct Pending {
        std::uint32_t node;
        double dev, upper, weighted;
    };
    std::vector<Pending> pending;
    std::vector<std::uint32_t> pending_order;
};

// Weigher::bound times this bounds the stored weights too (rounded up to float).
constexpr double k_rounded_weight = 1.0 + 1e-6;

// A swallowed node's place in a re-triangulated hole: its new triangle and its deviation there.
struct Assignment {
    std::uint32_t node;
    std::uint8_t triangle;
    float dev;
};

// One erase, enough to undo it exactly (see ErasedNodeRing): its ring's place in the ring pool.
// 8 bytes, with the ring's 4 per node beside it.
struct EraseRecord {
    std::uint32_t ring_begin = 0; // offset in the eraser's ring pool
    std::uint8_t ring_size = 0;
    std::uint8_t ring_capacity = 0; // room at ring_begin (a node erased again re-uses it)
    bool boundary = false;
};

// What an update needs to know of a live node without walking its fan (see update()).
struct LiveNode {
    std::uint32_t node;
    std::int32_t vertex; // its vertex (the node id itself unless Impl::lattice)
    Mesh::Point p;       // its point (an update reads it for every node it visits)
    // The node whose deviation gave the last evaluated cost, and that deviation: the cost under
    // any later view is at least star_dev times the star's weight there while the fan stands.
    std::uint32_t star;
    float star_dev;
    // Bounds on the fan's swallowed nodes: each lies within `reach` of the node (3-D) and deviates
    // at most `fan_dev` from its face. Raised as the fan changes, tightened when an update walks
    // the fan.
    float reach;
    float fan_dev;
    std::int32_t last_record; // the node's record from an earlier erase, -1 if none
    std::uint32_t cell;       // its cell of the update's grid (NodeEraser::Impl::cells)
    // For the screen model's updates, as logarithms (see Impl::face_seen_dev for the motion
    // factor that carries them to a later view): under the view of update seen_at, every node the
    // faces it seeds (see seed_fan) swallowed had a weighted deviation <= exp(seen_log) (+inf:
    // none known, dropped when the fan changes but by an update's erase, see carry_seen); under
    // the view of update low_at, its erase cost was >= exp(low_log) (-inf: none known, dropped
    // when it turns dirty; +inf: parked, see park).
    float seen_log = INFINITY;
    float low_log = -INFINITY;
    std::uint32_t seen_at = 0;
    std::uint32_t low_at = 0;
    bool seen_cone = false; // the fan's swallowed nodes were inside the view cone at seen_at
    bool fan_exact = false; // reach and fan_dev are fan_extent's for the fan as it stands
    // Once compact() ran (Impl::node_keys): the node's key and sweep stamp (see node_key).
    std::uint8_t stamp = 0;
    float key = 0.0f;
};

// What the faces of an erased node's fan knew of the samples they held, for the re-insert that
// brings the same triangles back (see reinsert): per fan face, in ring order, its worst sample,
// their largest deviation and its tile bounds (empty when it had none, see lattice_tiles).
struct KeptFan {
    std::vector<std::int32_t> head;
    std::vector<float> maxdev;
    std::vector<std::vector<float>> tiles;
};

// A run of a long swallowed list (see build_blocks).
struct Block {
    std::int32_t head;   // its first node
    std::uint32_t count; // its length
    double dev;          // >= the deviation of each of its nodes from the face
    glm::dvec3 lo, hi;   // the box of its nodes
};

// A square of the grid in xy that lets an update skip whole regions: bounds over the live nodes in
// it, kept conservative between updates (raised, or lowered for star_dev, as the nodes change).
struct Cell {
    float fan_dev = 0.0f;                  // >= every live node's fan_dev
    float reach = 0.0f;                    // >= every live node's reach
    float star_dev = 0.0f;                 // <= every live node's star_dev
    float zlo = INFINITY, zhi = -INFINITY; // the heights of every node in it, live or erased
    bool dirty = true;                     // some live node in it may be dirty
};

// An append-only array in chunks of 2^20 entries. It grows without moving what it holds (the
// history is most of a refiner's memory: a vector's reallocation copied all of it in one frame,
// 0.7 s of a 4097² flight's worst frame), and the entries one append takes never straddle two
// chunks, so run() sees them contiguous.
template <class T> class ChunkedPool {
  public:
    static constexpr std::size_t k_shift = 20, k_chunk = std::size_t(1) << k_shift;

    T &operator[](std::size_t i) { return chunks_[i >> k_shift][i & (k_chunk - 1)]; }
    const T &operator[](std::size_t i) const { return chunks_[i >> k_shift][i & (k_chunk - 1)]; }
    // The entries from i on that one append took.
    const T *run(std::size_t i) const { return &(*this)[i]; }
    // The index space in use (a chunk's unused tail counts when an append moved on).
    std::size_t size() const { return size_; }
    // Appends n value-initialised entries (n <= k_chunk) in one chunk; returns the first's index.
    std::size_t append(std::size_t n) {
        assert(n <= k_chunk);
        if (chunks_.empty() || chunks_.back().size() + n > k_chunk) {
            size_ = chunks_.size() << k_shift;
            chunks_.emplace_back();
        }
        std::vector<T> &last = chunks_.back();
        if (last.size() + n > last.capacity()) // doubling inside the chunk only
            last.reserve(std::min(k_chunk, std::max(2 * last.capacity(), last.size() + n)));
        last.resize(last.size() + n);
        const std::size_t first = size_;
        size_ += n;
        return first;
    }
    void shrink_to_fit() {
        if (!chunks_.empty())
            chunks_.back().shrink_to_fit();
    }
    std::size_t bytes() const {
        std::size_t b = chunks_.capacity() * sizeof(std::vector<T>);
        for (const std::vector<T> &c : chunks_)
            b += c.capacity() * sizeof(T);
        return b;
    }

  private:
    std::vector<std::vector<T>> chunks_;
    std::size_t size_ = 0;
};

constexpr std::uint8_t k_locked = 1;    // never erased (corner, general-mesh boundary, isolated)
constexpr std::uint8_t k_dirty = 2;     // its key predates a change of its neighbourhood
constexpr std::uint8_t k_recovered = 4; // recovered by the update under way
constexpr std::uint8_t k_unread = 8;    // a sample the input TIN left out, never live yet

constexpr std::int32_t k_absent = -1; // record_of of a sample the input TIN never held
// record_of of a sample left out whose ring is its lattice's regular one (RegularRings): no record.
constexpr std::int32_t k_regular_ring = std::numeric_limits<std::int32_t>::max();

} // namespace

struct NodeEraser::Impl {
    Mesh *mesh = nullptr; // borrowed from the caller
    EraseOptions options;
    bool has_view = false;
    View view;
    bool xy = true;
    double focal_distance = 1.0;
    Weigher weigher;          // pixels per unit deviation for the current view
    bool unit_weights = true; // no view, or the vertical model: every weight is 1
    // Per vertex while erase() runs (it asks for a node's weight again and again): the weigher at
    // the node rounded up, all computed in one run over the vertices when the view is set. The
    // erase asks for three of every four (N42E001 budget erase from the low view: 12 M look-ups of
    // 1.05 M weights out of 1.44 M), and the run and a plain array took 3-6 % off its time against
    // computing each on first use behind a per-vertex view stamp. An update computes each weight
    // where it needs it (as fast there, and 4 bytes per node less to keep).
    std::vector<float> weight;
    std::vector<float> face_maxdev;           // per face: bound on its swallowed nodes' deviation
    std::vector<std::int32_t> next_swallowed; // per vertex: next node in its face's list
    std::vector<std::int32_t> face_head;      // per face: first swallowed node, -1 none
    // Per vertex, with the lists: the face whose list holds it. A re-insert takes its node out of
    // that list, wherever it is: on a surface mesh a recovery files a swallowed node by its
    // projection on the recovered node's mean plane, which may put it under a face outside its own
    // ring (see reinsert).
    std::vector<std::int32_t> swallowed_by;
    // A grid TIN (see grid_width): the lattice's width. Its faces' swallowed nodes are the samples
    // inside them, scanned row by row: no lists (next_swallowed stays empty), and face_head holds
    // each face's worst sample.
    std::uint32_t grid_w = 0;
    // A sparse grid TIN (EraseOptions::lattice): the lattice's samples, and the columns' x and the
    // rows' y as the mesh's float points have them. Only the live samples have a vertex, in their
    // LiveNode (see vh), and sample_of maps each vertex to its sample; an erase frees its node's
    // vertex (free_vertices) for the next sample that enters or comes back, which takes its point
    // from here. Node ids are samples; without a lattice (a dense grid TIN or any mesh) they are
    // vertex indices, and sample_of stays empty.
    const Heightfield *lattice = nullptr;
    std::vector<float> lattice_x, lattice_y;
    double inverse_width = 0.0;
    std::vector<std::uint32_t> sample_of;
    OpenMesh::VPropHandleT<std::int64_t> origin; // a sparse lattice's: its vertices' samples
    std::uint32_t nodes = 0; // node ids: the lattice's samples, else the mesh's vertices
    // Per face: 1 when its list has blocks (face_blocks, see build_blocks), dropped when the list
    // is rebuilt.
    std::vector<std::uint8_t> face_blocked;
    std::unordered_map<std::int32_t, std::vector<Block>> face_blocks;
    // A grid TIN's large faces: a bound on their samples' deviation per tile (face_blocked is 1
    // for them too, see lattice_tiles).
    std::unordered_map<std::int32_t, std::vector<float>> face_tiles;
    // A grid TIN's lattice tiles (see lattice_tiles): the least and largest height of each, made
    // by rebind() or when a face is first tiled.
    std::vector<float> tile_z;
    // A shallow history's erased nodes whose fan covered more than k_kept_fan_samples samples of a
    // grid TIN: per fan face, what it knew of its samples (see KeptFan), by node.
    std::unordered_map<std::uint32_t, KeptFan> kept_fans;
    std::vector<std::int32_t> block_scratch; // build_blocks' scratch
    std::vector<std::uint8_t> block_cell_scratch;
    std::vector<std::int32_t> block_order_scratch;
    // Per face, for the screen model's updates: a bound on its swallowed nodes' weighted deviation
    // under the view of update face_seen[f] >> 1 (negative: none since the face last changed; the
    // low bit of face_seen[f]: they lay inside the view cone then, see weight_growth). When the
    // eye moves by d and the axis turns by a, a node's weight k / distance * peripheral(angle to
    // the axis) grows by at most (1 + d / distance') * exp((a + asin(d / distance')) / falloff), so
    // a face whose nodes were within the bound by that much is cleared without a scan (a still or
    // slow observer's frame on 4097²: 40 ms -> 10 ms). The views of the last k_seen_views updates
    // are kept; an older bound is dropped.
    std::vector<float> face_seen_dev;
    std::vector<std::uint32_t> face_seen;
    static constexpr std::uint32_t k_seen_views = 64;
    std::array<View, k_seen_views> seen_views;
    // For the update under way, per slot of seen_views: how far the eye has moved and the axis
    // turned since that view, and whether a bound made then carries over (the same lens).
    struct Since {
        double moved = 0.0, turn = 0.0;
        bool ok = false;
    };
    std::array<Since, k_seen_views> since;
    std::uint32_t updates = 0; // update() calls so far
    // Per vertex: its erase record (>= 0; k_regular_ring: none, see regular), k_absent for a
    // sample the input TIN never held (see the constructor), or for a live node -2 - its place in
    // live_list (so an update visits the live nodes without walking the whole terrain).
    std::vector<std::int32_t> record_of;
    // The samples a grid TIN left out take their rings from here where those are regular (all of
    // them on a 2^k + 1 grid), and keep a record only where not (EraseOptions::absent_history).
    std::unique_ptr<RegularRings> regular;
    std::vector<LiveNode> live_list; // the live nodes, in no order
    // The live nodes' and cells' fan bounds (reach, fan_dev) are not kept: only an update reads
    // them, so the constructor and erase() leave them, and the first update after them builds them
    // from the fans (rebuild_fans). Keeping them through a one-off erase cost 6 % of its time
    // (N42E001 budget erase from the low view, scratch runs).
    bool fans_stale = true;
    // The update's grid: cells of side cell_side from grid_lo, grid_nx per row, over the input's
    // extent in xy (grid_lo to grid_hi), sized for grid_live live nodes (see regrid).
    std::vector<Cell> cells;
    std::vector<std::uint8_t> cell_visit; // update's scratch: the cells that may matter
    glm::dvec2 grid_lo{0.0}, grid_hi{0.0};
    double cell_side = 1.0;
    std::int64_t grid_live = 0;
    double area_per_node = 0.0; // xy: the input's bounding-box area over its nodes
    int grid_nx = 1, grid_ny = 1;
    std::vector<std::uint8_t> flags; // per vertex: k_locked, k_dirty, k_recovered, k_unread
    // Per vertex: the sweep pass (mod 256) that last changed its ring.
    std::vector<std::uint8_t> stamp;
    // Set by compact(): the live nodes' keys and stamps are in their LiveNode, and the per-vertex
    // ones (heap, stamp) are freed, as only an update's sweeps, over live nodes, read them; 5
    // bytes per input node, and a stamp reset that visits the live nodes, not the terrain. The
    // next erase() goes back to the per-vertex arrays.
    bool node_keys = false;
    std::uint8_t pass = 0;
    std::size_t chain_cap = 0; // see sweep_node
    NodeHeap heap;
    ChunkedPool<EraseRecord> records;
    ChunkedPool<std::uint32_t> ring_pool;
    std::vector<EH> free_edges;
    std::vector<FH> free_faces;
    std::vector<VH> free_vertices; // a sparse lattice's: the vertices its erases freed
    std::int64_t live = 0, live_faces = 0;
    std::int64_t evaluations = 0;
    std::int64_t reerased = 0;    // the update under way's erases of nodes it recovered
    std::int64_t entered = 0;     // k_unread samples re-inserted so far
    std::int64_t fans_kept = 0;   // re-inserts whose fan faces took back a KeptFan so far
    bool absent_for_good = false; // some samples are k_absent: they can never enter
    Hole hole;
    std::vector<Assignment> assign; // swallowed node -> new triangle
    std::vector<std::uint32_t> swallowed_scratch;
    std::vector<std::uint32_t> chain; // the update's last dependency chain (see ready_dependency)
    // Where the mesh's vertex, edge and face arrays were when rebind() advised huge pages for them
    // (all null: never, as for a one-off erase).
    std::array<const void *, 3> advised{};
};

// The nearest float at or above (below) d: a bound stored as float is never understated
// (overstated).
static float float_up(double d) {
    const float f = float(d);
    return double(f) < d ? std::nextafter(f, INFINITY) : f;
}

static float float_down(double d) {
    const float f = float(d);
    return double(f) > d ? std::nextafter(f, -INFINITY) : f;
}

// ---- Node ids and vertices (see Impl::lattice) -------------------------------------------------

// These three run for most nodes an update touches: inlined wherever they are called (as calls
// they took 6 % of a 4097² fly-over's update time, scratch profile).

// The vertex of node x: invalid for a sparse lattice's sample that is not live. A live node's is
// in its LiveNode, not in an array over the samples (4 bytes each).
[[gnu::always_inline]] static inline VH vh(const NodeEraser::Impl &s, std::uint32_t x) {
    if (!s.lattice)
        return VH(int(x));
    const std::int32_t r = s.record_of[x];
    return r < -1 ? VH(s.live_list[std::size_t(-2 - r)].vertex) : VH();
}

// The node id of vertex v.
[[gnu::always_inline]] static inline std::uint32_t node_of(const NodeEraser::Impl &s, VH v) {
    return s.sample_of.empty() ? std::uint32_t(v.idx()) : s.sample_of[std::size_t(v.idx())];
}

// The point of node x, live or erased (a sparse lattice's sample has it without a vertex). Its
// row comes from a multiplication by 1 / width, corrected once: a division took most of the
// function's time.
[[gnu::always_inline]] static inline Mesh::Point node_point(const NodeEraser::Impl &s,
                                                            std::uint32_t x) {
    if (!s.lattice)
        return s.mesh->point(VH(int(x)));
    const auto w = std::uint32_t(s.lattice->width);
    auto r = std::uint32_t(double(x) * s.inverse_width);
    if (r * w > x)
        --r;
    else if ((r + 1) * w <= x)
        ++r;
    return {s.lattice_x[x - r * w], s.lattice_y[r], s.lattice->z[x]};
}

// A grid TIN's samples by lattice column and row: the mesh's points, or a sparse lattice's.
struct Samples {
    const Mesh::Point *pts = nullptr;                       // dense: vertex = sample
    const float *z = nullptr, *xs = nullptr, *ys = nullptr; // sparse
    std::int64_t w = 0;

    double x(std::int64_t c) const { return pts ? double(pts[c][0]) : double(xs[c]); }
    double y(std::int64_t r) const { return pts ? double(pts[r * w][1]) : double(ys[r]); }
    Mesh::Point at(std::int64_t c, std::int64_t r) const {
        return pts ? pts[r * w + c] : Mesh::Point(xs[c], ys[r], z[r * w + c]);
    }
    // Asks for the memory of samples first..last of row r (see scan_lattice).
    void prefetch(std::int64_t r, std::int64_t first, std::int64_t last) const {
        const char *a = pts ? reinterpret_cast<const char *>(pts + r * w + first)
                            : reinterpret_cast<const char *>(z + r * w + first);
        const char *b = pts ? reinterpret_cast<const char *>(pts + r * w + last + 1)
                            : reinterpret_cast<const char *>(z + r * w + last + 1);
        for (const char *line = a; line < b; line += 64)
            __builtin_prefetch(line);
    }
};

static Samples samples(const NodeEraser::Impl &s) {
    Samples g;
    g.w = s.grid_w;
    if (s.lattice) {
        g.z = s.lattice->z.data();
        g.xs = s.lattice_x.data();
        g.ys = s.lattice_y.data();
    } else {
        g.pts = s.mesh->points();
    }
    return g;
}

static std::uint32_t cell_of(const NodeEraser::Impl &s, const glm::dvec3 &p) {
    const int cx = std::clamp(int(std::floor((p.x - s.grid_lo.x) / s.cell_side)), 0, s.grid_nx - 1);
    const int cy = std::clamp(int(std::floor((p.y - s.grid_lo.y) / s.cell_side)), 0, s.grid_ny - 1);
    return std::uint32_t(cy * s.grid_nx + cx);
}

// The box that holds cell c's live nodes and, `reach` around them, their fans' swallowed nodes.
static std::pair<glm::dvec3, glm::dvec3> cell_box(const NodeEraser::Impl &s, std::uint32_t c,
                                                  double reach) {
    const Cell &cell = s.cells[c];
    const double margin = reach + 1e-6 * s.cell_side; // and the rounding of cell_of's division
    const glm::dvec2 lo =
        s.grid_lo + s.cell_side * glm::dvec2(int(c) % s.grid_nx, int(c) / s.grid_nx);
    return {{lo.x - margin, lo.y - margin, double(cell.zlo) - margin},
            {lo.x + s.cell_side + margin, lo.y + s.cell_side + margin, double(cell.zhi) + margin}};
}

// Makes x (vertex v) live; `record` is its record from an earlier erase (-1 if none), kept for
// re-use.
static void add_live(NodeEraser::Impl &s, std::uint32_t x, std::int32_t record, VH v) {
    const Mesh::Point point = node_point(s, x);
    const glm::dvec3 p = to_glm(point);
    const std::uint32_t c = cell_of(s, p);
    Cell &cell = s.cells[c];
    cell.zlo = std::min(cell.zlo, float_down(p.z));
    cell.zhi = std::max(cell.zhi, float_up(p.z));
    cell.star_dev = 0.0f;
    cell.dirty = true;
    s.record_of[x] = -2 - std::int32_t(s.live_list.size());
    LiveNode l{};
    l.node = x;
    l.vertex = v.idx();
    l.p = point;
    l.star = x;
    l.last_record = record;
    l.cell = c;
    s.live_list.push_back(l);
}

static LiveNode &live_node(NodeEraser::Impl &s, std::uint32_t x) {
    assert(s.record_of[x] < 0);
    return s.live_list[std::size_t(-2 - s.record_of[x])];
}

// Live node x's key (a lower bound of its cost under the current view; +inf: parked, or no erase
// possible until its ring changes) and its sweep stamp, wherever Impl::node_keys keeps them.
static float node_key(NodeEraser::Impl &s, std::uint32_t x) {
    return s.node_keys ? live_node(s, x).key : s.heap.key(x);
}
// The same for live node l at hand: without the look-up of its place in the live list (a cache
// miss per node of an update's walks over them).
static float node_key(const NodeEraser::Impl &s, const LiveNode &l) {
    return s.node_keys ? l.key : s.heap.key(l.node);
}
static void store_node_key(NodeEraser::Impl &s, std::uint32_t x, float key) {
    if (s.node_keys)
        live_node(s, x).key = key;
    else
        s.heap.store_key(x, key);
}
static void store_node_key(NodeEraser::Impl &s, LiveNode &l, float key) {
    if (s.node_keys)
        l.key = key;
    else
        s.heap.store_key(l.node, key);
}
static std::uint8_t &node_stamp(NodeEraser::Impl &s, std::uint32_t x) {
    return s.node_keys ? live_node(s, x).stamp : s.stamp[x];
}

// Face f's swallowed nodes change: its blocks and its seen bound go.
static void face_changed(NodeEraser::Impl &s, FH f) {
    s.face_seen_dev[f.idx()] = -1.0f;
    if (s.face_blocked[f.idx()]) {
        s.face_blocked[f.idx()] = 0;
        s.face_blocks.erase(f.idx());
        s.face_tiles.erase(f.idx());
    }
}

// Marks live node x dirty (its key predates a change of its fan).
static void mark_dirty(NodeEraser::Impl &s, std::uint32_t x) {
    s.flags[x] |= k_dirty;
    LiveNode &l = live_node(s, x);
    l.low_log = -INFINITY;
    s.cells[l.cell].dirty = true;
}

static void remove_live(NodeEraser::Impl &s, std::uint32_t x, std::int32_t record) {
    const std::int32_t place = -2 - s.record_of[x];
    const LiveNode last = s.live_list.back();
    s.live_list[std::size_t(place)] = last;
    s.record_of[last.node] = -2 - place;
    s.live_list.pop_back();
    s.record_of[x] = record;
}

// The ring of erased node x's last erase: its record's, or its regular one (written to `scratch`).
struct ErasedRing {
    const std::uint32_t *nodes;
    int size;
    bool boundary;
};

static ErasedRing erased_ring(const NodeEraser::Impl &s, std::uint32_t x,
                              std::array<std::uint32_t, 4> &scratch) {
    assert(s.record_of[x] >= 0);
    if (s.record_of[x] == k_regular_ring) {
        bool boundary = false;
        const int n = s.regular->ring(x, scratch.data(), boundary);
        return {scratch.data(), n, boundary};
    }
    const EraseRecord &record = s.records[std::size_t(s.record_of[x])];
    return {s.ring_pool.run(record.ring_begin), record.ring_size, record.boundary};
}

// The fans of the live nodes among the points p[0..count) (node ids `ids`, a hole's or a face's)
// now hold the triangles tri[0..ntri) over those points, whose swallowed nodes deviate at most
// dev[t]: widens each corner's bounds to cover its own new triangles, as fan_extent would from them
// (their farthest corner, plus their largest deviation). With bounds from the whole hole (its
// diameter and its largest deviation for every ring node) the 4097² fly-over at 30 fps walked 20 %
// more fans per update, 400-550 of them only to find the node's bounds clear it (scratch runs).
static void widen_fans(NodeEraser::Impl &s, const glm::dvec3 *p, const std::uint32_t *ids,
                       int count, const RingTriangle *tri, const float *dev, int ntri) {
    if (s.fans_stale)
        return;
    std::array<double, k_max_ring + 1> far2;
    std::array<float, k_max_ring + 1> most;
    std::fill_n(far2.begin(), count, 0.0);
    std::fill_n(most.begin(), count, 0.0f);
    for (int t = 0; t < ntri; ++t) {
        const std::uint8_t c[3] = {tri[t].a, tri[t].b, tri[t].c};
        for (int k = 0; k < 3; ++k) {
            const std::uint8_t i = c[k];
            for (int j = 1; j < 3; ++j) {
                const glm::dvec3 d = p[c[(k + j) % 3]] - p[i];
                far2[i] = std::max(far2[i], glm::dot(d, d));
            }
            most[i] = std::max(most[i], dev[t]);
        }
    }
    for (int i = 0; i < count; ++i) {
        if (s.record_of[ids[i]] >= 0)
            continue;
        LiveNode &l = live_node(s, ids[i]);
        l.seen_log = INFINITY;
        l.fan_exact = false;
        l.reach = std::max(l.reach, float_up(std::sqrt(far2[i]) + double(most[i])));
        l.fan_dev = std::max(l.fan_dev, most[i]);
        Cell &cell = s.cells[l.cell];
        cell.reach = std::max(cell.reach, l.reach);
        cell.fan_dev = std::max(cell.fan_dev, l.fan_dev);
    }
}

// Adds node u, deviating `dev` from face f, to f's list. The list's head stays its node of largest
// deviation (the rest in no order), so evaluate can try every fan face's worst node before it walks
// the lists.
static void push_swallowed(NodeEraser::Impl &s, int f, std::uint32_t u, float dev) {
    const std::int32_t head = s.face_head[f];
    s.swallowed_by[u] = f;
    if (head < 0 || dev > s.face_maxdev[f]) {
        s.next_swallowed[u] = head;
        s.face_head[f] = std::int32_t(u);
        s.face_maxdev[f] = std::max(s.face_maxdev[f], dev);
    } else {
        s.next_swallowed[u] = s.next_swallowed[head];
        s.next_swallowed[head] = std::int32_t(u);
    }
}

// Takes node u out of face f's list (the face keeps its deviation bound, now perhaps loose).
static void unlink_swallowed(NodeEraser::Impl &s, std::int32_t f, std::uint32_t u) {
    std::int32_t *link = &s.face_head[std::size_t(f)];
    while (*link != std::int32_t(u))
        link = &s.next_swallowed[std::size_t(*link)];
    *link = s.next_swallowed[u];
    face_changed(s, FH(f)); // its blocks are runs of the list
}

// ---- Geometry of a hole ------------------------------------------------------------------------

static glm::dvec2 project(const Hole &h, const glm::dvec3 &p) {
    const glm::dvec3 d = p - h.origin;
    return {glm::dot(d, h.ex), glm::dot(d, h.ey)};
}

// The frame of the triangle with projected corners qa, qb, qc; `xy`: its heights za, zb, zc too.
static TriangleFrame triangle_frame(const glm::dvec2 &qa, const glm::dvec2 &qb,
                                    const glm::dvec2 &qc, bool xy, double za = 0.0, double zb = 0.0,
                                    double zc = 0.0) {
    const double inv = 1.0 / orient(qa, qb, qc);
    TriangleFrame f;
    // w0 = orient(qb, qc, x) / area, w1 = orient(qc, qa, x) / area
    f.w0 = glm::dvec3(qb.y - qc.y, qc.x - qb.x, qb.x * qc.y - qc.x * qb.y) * inv;
    f.w1 = glm::dvec3(qc.y - qa.y, qa.x - qc.x, qc.x * qa.y - qa.x * qc.y) * inv;
    if (xy) {
        const glm::dvec3 w2 = glm::dvec3(0.0, 0.0, 1.0) - f.w0 - f.w1;
        f.height = f.w0 * za + f.w1 * zb + w2 * zc;
        f.slope = std::sqrt(f.height.x * f.height.x + f.height.y * f.height.y);
    }
    return f;
}

// Fills the affine frames of the hole's new triangles.
static void frame_triangles(const NodeEraser::Impl &s, Hole &h) {
    for (int t = 0; t < h.ntri; ++t) {
        const RingTriangle &tri = h.tri[t];
        TriangleFrame &f = h.frame[t];
        f = triangle_frame(h.q[tri.a], h.q[tri.b], h.q[tri.c], s.xy, h.p[tri.a].z, h.p[tri.b].z,
                           h.p[tri.c].z);
    }
}

// What rounding every corner of a TIN triangle of this slope (|grad z|) to float can move its
// interpolant at a point whose largest coordinate magnitude is `coord`: a few ulp of it. The mesh
// holds float coordinates of exact grid positions, so deviations are widened by this.
static double rounding_margin(double coord, double slope) {
    const double ulp = 1.2e-7 * std::max(coord, 1.0);
    return 4.0 * ulp * slope;
}

// A TIN point's vertical deviation from the triangle of frame f, widened by the rounding margin.
static double vertical_dev(const TriangleFrame &f, double x, double y, double z) {
    return std::abs(z - (f.height.x * x + f.height.y * y + f.height.z)) +
           rounding_margin(std::max(std::abs(x), std::abs(y)), f.slope);
}

// vertical_dev over one triangle of a grid TIN with corners a, b, c, its rounding margin taken
// where it is largest in the triangle (at the corner farthest from the axes).
class PlaneDev {
  public:
    PlaneDev(const TriangleFrame &f, const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c)
        : h_(f.height) {
        const double far = std::max({std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y),
                                     std::abs(c.x), std::abs(c.y)});
        margin_ = rounding_margin(far, f.slope);
    }
    double operator()(const Mesh::Point &p) const {
        const double z = h_.x * double(p[0]) + h_.y * double(p[1]) + h_.z;
        return std::abs(double(p[2]) - z) + margin_;
    }

  private:
    glm::dvec3 h_;
    double margin_;
};

// The new triangle covering p (the one where p's smallest weight is largest), and p's deviation
// from it: vertical for a TIN, its distance to the triangle otherwise (a bound of its distance to
// the surface; the distance to the triangle's plane is not, where the triangle is steep in the
// projection plane). `inside`, if given, tells whether that triangle covers p (projected, edges
// included) or is only the nearest.
static std::uint8_t locate(const NodeEraser::Impl &s, const Hole &h, const glm::dvec3 &p,
                           double &dev, bool *inside = nullptr) {
    const glm::dvec2 x2 = project(h, p);
    const glm::dvec3 x(x2.x, x2.y, 1.0);
    int best = 0;
    double best_min = -INFINITY;
    for (int t = 0; t < h.ntri; ++t) {
        const double b0 = glm::dot(h.frame[t].w0, x), b1 = glm::dot(h.frame[t].w1, x);
        const double lowest = std::min({b0, b1, 1.0 - b0 - b1});
        if (lowest > best_min) {
            best_min = lowest;
            best = t;
        }
        if (lowest >= 0.0)
            break; // inside (or on the edge of) this triangle
    }
    if (inside)
        *inside = best_min >= 0.0;
    const RingTriangle &t = h.tri[best];
    dev = s.xy ? vertical_dev(h.frame[best], p.x, p.y, p.z)
               : triangle_distance(p, h.p[t.a], h.p[t.b], h.p[t.c]);
    return std::uint8_t(best);
}

// ---- Grid TINs ---------------------------------------------------------------------------------
// A TIN whose nodes are all the samples of a w x h lattice, node r * w + c at column c of row r
// (grid_tin's layout): the nodes a face swallowed are exactly the samples inside it other than its
// corners, so they are scanned row by row from the lattice instead of kept in lists. A scan reads
// the points in memory order and needs no locate, and a face that changes moves no node.

// The lattice's width when the mesh is such a TIN (every point on the lattice its first row and
// column span, in order), else 0.
static std::uint32_t grid_width(const Mesh &m) {
    const std::size_t n = m.n_vertices();
    if (n < 4 || n > std::size_t(std::numeric_limits<std::int32_t>::max()))
        return 0;
    const Mesh::Point *p = m.points();
    std::size_t w = 1;
    while (w < n && p[w][1] == p[0][1])
        ++w;
    if (w < 2 || w == n || n % w != 0)
        return 0;
    const auto monotone = [](float a, float b, float c) { return (a < b) == (b < c) && b != c; };
    for (std::size_t c = 2; c < w; ++c)
        if (!monotone(p[c - 2][0], p[c - 1][0], p[c][0]))
            return 0;
    for (std::size_t r = 2 * w; r < n; r += w)
        if (!monotone(p[r - 2 * w][1], p[r - w][1], p[r][1]))
            return 0;
    if (p[0][0] == p[1][0] || p[0][1] == p[w][1])
        return 0;
    for (std::size_t r = 0; r < n; r += w)
        for (std::size_t c = 0; c < w; ++c)
            if (p[r + c][0] != p[c][0] || p[r + c][1] != p[r][1])
                return 0;
    return std::uint32_t(w);
}

constexpr std::int64_t k_band_rows = 16;

// Visits the nodes a face with corner nodes a, b, c of a grid TIN swallowed, band by band of
// k_band_rows rows: band(lo, hi) gets the xy box of the band's samples and returns a value
// visit(u, p, value) is given for each sample u (point p) of the band, or a negative value to skip
// the band. visit returns false to stop the scan; then so does scan_lattice, and so does band_end,
// called after each band's samples.
template <class Band, class Visit, class BandEnd = bool (*)()>
static bool scan_lattice(
    const NodeEraser::Impl &s, std::uint32_t a, std::uint32_t b, std::uint32_t c, const Band &band,
    const Visit &visit, const BandEnd &band_end = [] { return true; }) {
    const std::int64_t w = s.grid_w;
    const LatticeTriangle t(s.grid_w, a, b, c);
    const Samples g = samples(s);
    // Left uninitialised (a std::pair would be zeroed on every call, 1 % of an erase's time): each
    // band writes the spans of its rows before it reads them.
    struct Span {
        std::int64_t first, second;
    };
    std::array<Span, k_band_rows> spans;
    for (std::int64_t y0 = t.first_row; y0 <= t.last_row; y0 += k_band_rows) {
        const std::int64_t y1 = std::min(y0 + k_band_rows - 1, t.last_row);
        std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = -1;
        for (std::int64_t y = y0; y <= y1; ++y) {
            const auto [first, last] = t.span(y);
            spans[y - y0] = {first, last};
            if (spans[y - y0].first <= spans[y - y0].second) {
                lo = std::min(lo, spans[y - y0].first);
                hi = std::max(hi, spans[y - y0].second);
            }
        }
        if (lo > hi)
            continue;
        const double xa = g.x(lo), xb = g.x(hi), ya = g.y(y0), yb = g.y(y1);
        const double value = band(glm::dvec2(std::min(xa, xb), std::min(ya, yb)),
                                  glm::dvec2(std::max(xa, xb), std::max(ya, yb)));
        if (value < 0.0)
            continue;
        // The band's rows lie a lattice row apart in memory, too far for the hardware to guess:
        // asking for all of them before the first is read overlaps their cache misses. The 4097²
        // flight's updates at 30 frames per second took 4-16 % less (scratch runs, p50 of 300
        // frames of each path); the 1201² erase, whose rows stay cached, the same.
        for (std::int64_t y = y0; y <= y1; ++y)
            g.prefetch(y, spans[y - y0].first, spans[y - y0].second);
        for (std::int64_t y = y0; y <= y1; ++y)
            for (std::int64_t x = spans[y - y0].first; x <= spans[y - y0].second; ++x) {
                const std::uint32_t u = std::uint32_t(y * w + x);
                if (u != a && u != b && u != c && !visit(u, g.at(x, y), value))
                    return false;
            }
        if (!band_end())
            return false;
    }
    return true;
}

// A grid TIN's face over more than k_tiled_samples samples (a far flat, a slope seen from afar:
// on 4097² a face can hold millions) keeps a bound on its samples' deviation per tile of the
// lattice's grid of k_band_rows rows by k_tile_cols columns, so that a check weighs only the tiles
// whose deviation can matter, where a band's bound must take the face's largest deviation. A low
// observer's frames on 4097² re-checked a few such faces of the far edge each, 5-30 ms apiece.
// The bounds come from each tile's height range (Impl::tile_z) against the face's plane, with no
// sample read: a pass over every sample of a face that covers most of the terrain was most of the
// slowest frames of a descent from high above (36 of 57 ms, scratch runs on 4097²). A tile's scan
// then tightens its bound to its samples' largest deviation.
constexpr std::int64_t k_tile_cols = 64;
constexpr std::int64_t k_tiled_samples = 16384;
// A shallow history keeps what the fan faces of an erase knew of their samples (KeptFan) when they
// held more than this many in all: a re-insert then scans none of them (face_worst).
constexpr std::int64_t k_kept_fan_samples = k_tiled_samples;

// The lattice's tiles: tile (r / k_band_rows, c / k_tile_cols) holds sample (c, r).
static std::int64_t tile_columns(const NodeEraser::Impl &s) {
    return (std::int64_t(s.grid_w) - 1) / k_tile_cols + 1;
}

// The least and largest height of each tile of a grid TIN's lattice (one pass over the samples).
static void build_tile_z(NodeEraser::Impl &s) {
    const std::int64_t w = s.grid_w, rows = std::int64_t(s.nodes) / w;
    const std::int64_t columns = tile_columns(s);
    s.tile_z.assign(std::size_t(2 * columns * ((rows - 1) / k_band_rows + 1)), 0.0f);
    const Samples g = samples(s);
    for (std::int64_t r = 0; r < rows; ++r) {
        float *band = s.tile_z.data() + 2 * (r / k_band_rows) * columns;
        for (std::int64_t c0 = 0; c0 < w; c0 += k_tile_cols) {
            float lo = INFINITY, hi = -INFINITY;
            for (std::int64_t c = c0; c < std::min(w, c0 + k_tile_cols); ++c) {
                lo = std::min(lo, g.at(c, r)[2]);
                hi = std::max(hi, g.at(c, r)[2]);
            }
            float *tile = band + 2 * (c0 / k_tile_cols);
            if (r % k_band_rows == 0) {
                tile[0] = lo;
                tile[1] = hi;
            } else {
                tile[0] = std::min(tile[0], lo);
                tile[1] = std::max(tile[1], hi);
            }
        }
    }
}

// The tiling of face (a, b, c): its rows, and the lattice tiles over its box, bands from row0 and
// columns from x0 (multiples of the tile's sides).
struct Tiling {
    LatticeTriangle t;
    std::int64_t row0, x0, columns; // tile columns: [x0 + k * k_tile_cols, ... + k_tile_cols)
};

static Tiling tiling(const NodeEraser::Impl &s, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const std::int64_t w = s.grid_w;
    const std::int64_t x0 = std::min({a % w, b % w, c % w}) / k_tile_cols * k_tile_cols,
                       x1 = std::max({a % w, b % w, c % w});
    const LatticeTriangle t(s.grid_w, a, b, c);
    return {t, t.first_row / k_band_rows * k_band_rows, x0, (x1 - x0) / k_tile_cols + 1};
}

// Visits the samples of face (a, b, c) tile by tile: tile(lo, hi, bound) gets the xy box of a
// tile's samples and the bound on their deviation, and returns the value visit(u, q, dev, value)
// is given for each of them (q its point, dev = deviation(q)), or a negative value to skip the
// tile. A tile visited lowers its bound in `dev` to its samples' largest deviation.
template <class Tile, class Deviation, class Visit>
static void scan_tiles(const NodeEraser::Impl &s, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                       std::vector<float> &dev, const Tile &tile, const Deviation &deviation,
                       const Visit &visit) {
    const std::int64_t w = s.grid_w;
    const Tiling g = tiling(s, a, b, c);
    const Samples lattice = samples(s);
    std::array<std::pair<std::int64_t, std::int64_t>, k_band_rows> spans;
    for (std::int64_t y0 = g.row0; y0 <= g.t.last_row; y0 += k_band_rows) {
        const std::int64_t ya = std::max(y0, g.t.first_row),
                           y1 = std::min(y0 + k_band_rows - 1, g.t.last_row);
        const std::int64_t band = (y0 - g.row0) / k_band_rows;
        std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = -1;
        for (std::int64_t y = ya; y <= y1; ++y) {
            spans[y - y0] = g.t.span(y);
            if (spans[y - y0].first <= spans[y - y0].second) {
                lo = std::min(lo, spans[y - y0].first);
                hi = std::max(hi, spans[y - y0].second);
            }
        }
        if (lo > hi)
            continue;
        for (std::int64_t k = (lo - g.x0) / k_tile_cols; k <= (hi - g.x0) / k_tile_cols; ++k) {
            float &bound = dev[std::size_t(band * g.columns + k)];
            const std::int64_t c0 = std::max(lo, g.x0 + k * k_tile_cols),
                               c1 = std::min(hi, g.x0 + (k + 1) * k_tile_cols - 1);
            const double xa = lattice.x(c0), xb = lattice.x(c1), yl = lattice.y(ya),
                         yh = lattice.y(y1);
            const double value =
                tile(glm::dvec2(std::min(xa, xb), std::min(yl, yh)),
                     glm::dvec2(std::max(xa, xb), std::max(yl, yh)), double(bound));
            if (value < 0.0)
                continue;
            double most = 0.0;
            for (std::int64_t y = ya; y <= y1; ++y)
                for (std::int64_t x = std::max(c0, spans[y - y0].first),
                                  end = std::min(c1, spans[y - y0].second);
                     x <= end; ++x) {
                    const std::uint32_t u = std::uint32_t(y * w + x);
                    if (u == a || u == b || u == c)
                        continue;
                    const glm::dvec3 q = to_glm(lattice.at(x, y));
                    const double d = deviation(q);
                    most = std::max(most, d);
                    visit(u, q, d, value);
                }
            bound = std::min(bound, float_up(most));
        }
    }
}

// Face f's tiles (corners a, b, c): kept ones, made now when the face holds more than
// k_tiled_samples samples, else null. A tile's bound is the largest distance from the height
// range of its lattice tile to `plane(x, y)` (the face's height) over its box, widened like a
// deviation (rounding_margin at its farthest corner for the face's slope, and a hair for the
// rounding of these sums); no sample is read.
template <class Plane>
static std::vector<float> *lattice_tiles(NodeEraser::Impl &s, FH f, std::uint32_t a,
                                         std::uint32_t b, std::uint32_t c, const Plane &plane,
                                         double slope) {
    if (s.face_blocked[f.idx()]) {
        const auto kept = s.face_tiles.find(f.idx());
        return kept == s.face_tiles.end() ? nullptr : &kept->second;
    }
    const Tiling g = tiling(s, a, b, c);
    const std::int64_t rows = g.t.last_row - g.t.first_row + 1;
    if (rows * g.columns * k_tile_cols / 2 <= k_tiled_samples)
        return nullptr; // half its box: at most about k_tiled_samples samples
    if (s.tile_z.empty())
        build_tile_z(s);
    const std::int64_t w = s.grid_w, columns = tile_columns(s);
    const std::int64_t x_lo = std::min({a % w, b % w, c % w}),
                       x_hi = std::max({a % w, b % w, c % w});
    const Samples lattice = samples(s);
    const std::int64_t bands = (g.t.last_row - g.row0) / k_band_rows + 1;
    std::vector<float> dev(std::size_t(bands * g.columns));
    for (std::int64_t j = 0; j < bands; ++j) {
        const std::int64_t r0 = std::max(g.row0 + j * k_band_rows, g.t.first_row),
                           r1 = std::min(g.row0 + (j + 1) * k_band_rows - 1, g.t.last_row);
        const double y0 = lattice.y(r0), y1 = lattice.y(r1);
        for (std::int64_t k = 0; k < g.columns; ++k) {
            const std::int64_t c0 = std::max(g.x0 + k * k_tile_cols, x_lo),
                               c1 = std::min(g.x0 + (k + 1) * k_tile_cols - 1, x_hi);
            const double x0 = lattice.x(c0), x1 = lattice.x(c1);
            const float *z = s.tile_z.data() +
                             2 * ((g.row0 / k_band_rows + j) * columns + (g.x0 / k_tile_cols + k));
            const double p[4] = {plane(x0, y0), plane(x1, y0), plane(x0, y1), plane(x1, y1)};
            const double pl = std::min({p[0], p[1], p[2], p[3]}),
                         ph = std::max({p[0], p[1], p[2], p[3]});
            const double far = std::max({std::abs(x0), std::abs(x1), std::abs(y0), std::abs(y1)});
            const double most = std::max({double(z[1]) - pl, ph - double(z[0]), 0.0});
            dev[std::size_t(j * g.columns + k)] =
                float_up(most + rounding_margin(far, slope) +
                         1e-9 * (std::abs(pl) + std::abs(ph) + std::abs(double(z[0])) +
                                 std::abs(double(z[1])) + 1.0));
        }
    }
    s.face_blocked[f.idx()] = 1;
    return &(s.face_tiles[f.idx()] = std::move(dev));
}

// The samples strictly inside a grid TIN's hole (the node itself among them), by Pick's theorem:
// the ring's area in lattice cells less half the samples on it, plus one.
static std::int64_t lattice_inside(const NodeEraser::Impl &s, const Hole &h) {
    const std::int64_t w = s.grid_w;
    std::int64_t twice = 0, on_ring = 0;
    for (int i = 0; i < h.n; ++i) {
        const std::int64_t a = node_of(s, h.r[i]), b = node_of(s, h.r[(i + 1) % h.n]);
        twice += (a % w) * (b / w) - (b % w) * (a / w);
        on_ring += std::gcd(std::abs(b % w - a % w), std::abs(b / w - a / w));
    }
    return (std::abs(twice) - on_ring) / 2 + 1;
}

// The largest deviation (rounded up) of the samples a grid TIN's face with corner nodes a, b, c
// (points pa, pb, pc, frame f) swallowed, and the sample that has it (-1 when none deviates).
static std::pair<float, std::int32_t> face_worst(const NodeEraser::Impl &s, std::uint32_t a,
                                                 std::uint32_t b, std::uint32_t c,
                                                 const TriangleFrame &f, const glm::dvec3 &pa,
                                                 const glm::dvec3 &pb, const glm::dvec3 &pc) {
    const PlaneDev deviation(f, pa, pb, pc);
    double maxdev = 0.0;
    std::int32_t worst = -1;
    scan_lattice(
        s, a, b, c, [](const glm::dvec2 &, const glm::dvec2 &) { return 0.0; },
        [&](std::uint32_t u, const Mesh::Point &p, double) {
            const double dev = deviation(p);
            if (dev > maxdev) {
                maxdev = dev;
                worst = std::int32_t(u);
            }
            return true;
        });
    return {float_up(maxdev), worst};
}

static HH find_halfedge(const Mesh &m, VH a, VH b) {
    const HH start = m.halfedge_handle(a);
    if (!start.is_valid())
        return HH();
    HH he = start;
    for (int guard = 0; guard < 4 * k_max_ring; ++guard) {
        if (m.to_vertex_handle(he) == b)
            return he;
        he = m.next_halfedge_handle(m.opposite_halfedge_handle(he));
        if (he == start)
            break;
    }
    return HH();
}

// Spokes of v counter-clockwise; false for an isolated, complex or too-high-valence node.
static bool gather_ring(const Mesh &m, VH v, Hole &h, int max_valence) {
    const HH start = m.halfedge_handle(v);
    if (!start.is_valid())
        return false;
    h.v = v;
    h.boundary = m.is_boundary(start);
    const HH h0 = h.boundary ? m.opposite_halfedge_handle(m.prev_halfedge_handle(start)) : start;
    const int limit = std::min(max_valence + 1, k_max_ring);
    int n = 0;
    HH he = h0;
    do {
        if (n == limit)
            return false;
        h.h[n] = he;
        h.r[n] = m.to_vertex_handle(he);
        ++n;
        if (h.boundary && m.is_boundary(he))
            break;
        he = m.opposite_halfedge_handle(m.prev_halfedge_handle(he));
    } while (he != h0);
    h.n = n;
    if (h.boundary && he != start)
        return false; // a second boundary fan: a complex vertex
    return n >= 3;
}

// Node `node`'s weight under the current view: the weigher at the node rounded up to a float,
// from Impl::weight when it is kept.
static double weight_of(const NodeEraser::Impl &s, std::uint32_t node) {
    if (s.unit_weights)
        return 1.0;
    if (!s.weight.empty())
        return double(s.weight[node]);
    return double(float_up(s.weigher(to_glm(node_point(s, node)))));
}

static double weighted(const NodeEraser::Impl &s, std::uint32_t node, double dev) {
    return dev > 0.0 ? dev * weight_of(s, node) : 0.0;
}

// The weights for a new view (s.weigher): `keep` computes them for every vertex (erase), else
// they go (each is computed where it is needed).
static void new_weights(NodeEraser::Impl &s, bool keep) {
    s.unit_weights = !s.has_view || s.options.significance.model == SpModel::vertical;
    if (s.unit_weights || !keep) {
        std::vector<float>().swap(s.weight);
        return;
    }
    s.weight.resize(s.nodes);
    for (std::uint32_t x = 0; x < s.nodes; ++x)
        s.weight[x] = float_up(s.weigher(to_glm(node_point(s, x))));
}

// ---- Stages ------------------------------------------------------------------------------------

// classify: which nodes may ever be erased, and each node's weight.
static void classify_nodes(NodeEraser::Impl &s) {
    const Mesh &m = *s.mesh;
    s.flags.resize(s.nodes);
    for (std::uint8_t &f : s.flags)
        f &= k_unread;
    if (s.node_keys)
        for (LiveNode &l : s.live_list)
            l.stamp = 0;
    else
        s.stamp.assign(s.nodes, 0);
    s.pass = 0;
    for (auto v : m.vertices()) {
        const HH he = m.halfedge_handle(v);
        if (!he.is_valid() || (m.is_boundary(he) && (!s.xy || !s.options.erase_boundary)))
            s.flags[node_of(s, v)] |= k_locked;
    }
    for (std::size_t x = 0; x < s.record_of.size(); ++x)
        if (s.record_of[x] == k_absent)
            s.flags[x] |= k_locked;
    s.weigher = Weigher(s.has_view ? &s.view : nullptr, s.options.significance);
    new_weights(s, true);
}

// A bound of the stored weights of the nodes a TIN face with corners a, b, c swallowed, which lie
// in its corners' box in xy and within `maxdev` of it in z (with a margin for the float rounding
// of maxdev and of the deviations' recomputation).
static double swallowed_weight_bound(const NodeEraser::Impl &s, const glm::dvec3 &a,
                                     const glm::dvec3 &b, const glm::dvec3 &c, float maxdev) {
    const glm::dvec3 dz(0.0, 0.0, 1.001 * double(maxdev));
    return s.weigher.bound(glm::min(glm::min(a, b), c) - dz, glm::max(glm::max(a, b), c) + dz) *
           k_rounded_weight;
}

// The cost and its node after the samples of h.pending, as raising the cost sample by sample in
// scan order would leave them (the first node whose weighted deviation exceeds `limit`, else the
// first of the largest above the cost), weighing fewer of them: by their bound, largest first, once
// one exceeding the limit is ruled out. False when the cost exceeds `limit`.
static bool raise_pending(const NodeEraser::Impl &s, Hole &h, double limit) {
    std::vector<Hole::Pending> &p = h.pending;
    for (Hole::Pending &q : p)
        if (q.upper > limit) {
            q.weighted = weighted(s, q.node, q.dev);
            if (q.weighted > limit) {
                h.cost = q.weighted;
                h.star = q.node;
                h.star_dev = q.dev;
                p.clear();
                return false;
            }
        }
    std::vector<std::uint32_t> &order = h.pending_order;
    order.resize(p.size());
    for (std::uint32_t i = 0; i < std::uint32_t(p.size()); ++i)
        order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return p[a].upper > p[b].upper; });
    double best = h.cost;
    std::int64_t best_at = -1; // -1: the cost before the band
    for (const std::uint32_t i : order) {
        Hole::Pending &q = p[i];
        if (q.upper < best)
            break; // nor any after it: its weighted deviation is at most its bound
        if (q.weighted < 0.0)
            q.weighted = weighted(s, q.node, q.dev);
        if (q.weighted > best || (q.weighted == best && best_at > std::int64_t(i))) {
            best = q.weighted;
            best_at = i;
        }
    }
    if (best_at >= 0) {
        h.cost = best;
        h.star = p[std::size_t(best_at)].node;
        h.star_dev = p[std::size_t(best_at)].dev;
    }
    p.clear();
    return true;
}

// evaluate's walk over the nodes a grid TIN's hole swallows (v at pv among them): each new
// triangle's samples, with their largest deviation and worst sample kept for retriangulate. A
// sample whose deviation times the largest weight in its band's box (within the old fan's largest
// deviation of its corners' heights) could raise the cost waits for the band's end
// (raise_pending), which weighs few of them: raised one by one in scan order, each raise made the
// next sample's weight look worth computing (45 % of an update's weights on the 4097² flights). A
// sample whose bound exceeds `limit` settles the band's samples so far at once, so a failing
// evaluation stops where it did (waiting for the band's end took 10 % more time than raising one by
// one; settling early, 2-4 % less). Stops once the cost exceeds `limit`; sets h.deferred instead
// when the hole holds more than `max_swallowed` samples.
static void scan_hole(const NodeEraser::Impl &s, Hole &h, const glm::dvec3 &pv, double limit,
                      std::size_t max_swallowed) {
    if (std::size_t(lattice_inside(s, h)) > max_swallowed) {
        h.deferred = true;
        return;
    }
    const Mesh &m = *s.mesh;
    float fan_dev = 0.0f;
    double zlo = pv.z, zhi = pv.z;
    for (int i = 0; i < h.n; ++i) {
        zlo = std::min(zlo, h.p[i].z);
        zhi = std::max(zhi, h.p[i].z);
        const FH f = m.face_handle(h.h[i]);
        if (f.is_valid())
            fan_dev = std::max(fan_dev, s.face_maxdev[f.idx()]);
    }
    const double dz = 1.001 * double(fan_dev);
    const auto band = [&](const glm::dvec2 &lo, const glm::dvec2 &hi) {
        return s.unit_weights ? 1.0
                              : s.weigher.bound({lo, zlo - dz}, {hi, zhi + dz}) * k_rounded_weight;
    };
    for (int t = 0; t < h.ntri; ++t) {
        const PlaneDev deviation(h.frame[t], h.p[h.tri[t].a], h.p[h.tri[t].b], h.p[h.tri[t].c]);
        double maxdev = 0.0;
        std::int32_t worst = -1;
        const bool whole = scan_lattice(
            s, node_of(s, h.r[h.tri[t].a]), node_of(s, h.r[h.tri[t].b]),
            node_of(s, h.r[h.tri[t].c]), band,
            [&](std::uint32_t u, const Mesh::Point &p, double bound) {
                const double dev = deviation(p);
                if (dev > maxdev) {
                    maxdev = dev;
                    worst = std::int32_t(u);
                }
                const double upper = dev * bound;
                if (!(upper > h.cost))
                    return true;
                h.pending.push_back({u, dev, upper, -1.0});
                return !(upper > limit) || raise_pending(s, h, limit);
            },
            [&] { return raise_pending(s, h, limit); });
        h.tri_maxdev[t] = float_up(maxdev);
        h.tri_worst[t] = worst;
        if (!whole)
            return;
    }
}

// How far past the limit evaluate's scan of a grid TIN's hole measures the cost (see there). On
// the 4097² first flights at 30 frames per second (scratch runs, the same TINs): 12-22 % fewer
// candidates, the erase 4-23 % faster (paths' speed) and 12-19 % (a quarter of it); from 1.5 to
// the whole hole it made no difference.
constexpr double k_scan_reach = 2.0;

// Re-triangulates v's hole into s.hole and measures the erase's cost (exactly up to `limit`, beyond
// it only as some value > limit); false when v cannot be erased without a fold-over, a
// non-manifold edge or a moved outline. With more than `max_swallowed` nodes under the fan it
// stops and sets hole.deferred.
static bool evaluate(NodeEraser::Impl &s, VH v, double limit,
                     std::size_t max_swallowed = std::numeric_limits<std::size_t>::max()) {
    ++s.evaluations;
    Hole &h = s.hole;
    h.deferred = false;
    const Mesh &m = *s.mesh;
    if (!gather_ring(m, v, h, s.options.max_valence))
        return false;
    const int n = h.n;
    const glm::dvec3 pv = to_glm(m.point(v));
    for (int i = 0; i < n; ++i)
        h.p[i] = to_glm(m.point(h.r[i]));
    const int fans = h.boundary ? n - 1 : n;
    if (s.xy) {
        h.origin = glm::dvec3(0.0);
        h.ex = {1, 0, 0};
        h.ey = {0, 1, 0};
        for (int i = 0; i < n; ++i)
            h.q[i] = {h.p[i].x, h.p[i].y};
        if (h.boundary) {
            const glm::dvec2 c(pv.x, pv.y);
            if (orient(h.q[0], c, h.q[n - 1]) != 0.0 || glm::dot(h.q[0] - c, h.q[n - 1] - c) >= 0.0)
                return false; // erasing it would move the outline
        }
    } else {
        glm::dvec3 normal(0.0);
        for (int i = 0; i < fans; ++i)
            normal += glm::cross(h.p[i] - pv, h.p[(i + 1) % n] - pv);
        const double len = glm::length(normal);
        if (!(len > 0.0))
            return false;
        const glm::dvec3 ez = normal / len;
        const glm::dvec3 helper = std::abs(ez.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        h.origin = pv;
        h.ex = glm::normalize(glm::cross(helper, ez));
        h.ey = glm::cross(ez, h.ex);
        for (int i = 0; i < n; ++i)
            h.q[i] = project(h, h.p[i]);
        for (int i = 0; i < fans; ++i)
            if (orient(glm::dvec2(0.0), h.q[i], h.q[(i + 1) % n]) <= 0.0)
                return false; // the fan is not star-shaped in its mean plane
    }
    h.ntri = clip_ears(h.q.data(), n, h.tri.data());
    if (h.ntri != n - 2)
        return false;
    frame_triangles(s, h);
    if (!s.xy)
        for (int t = 0; t < h.ntri; ++t) {
            const std::uint8_t c[3] = {h.tri[t].a, h.tri[t].b, h.tri[t].c};
            for (int k = 0; k < 3; ++k) {
                const int a = c[k], b = c[(k + 1) % 3];
                if (b == (a + 1) % n)
                    continue; // a ring edge
                if (find_halfedge(m, h.r[a], h.r[b]).is_valid())
                    return false; // the diagonal exists outside the hole: non-manifold
            }
        }
    s.assign.clear();
    double dev = 0.0;
    const std::uint8_t own = locate(s, h, pv, dev);
    const std::uint32_t x = node_of(s, v);
    s.assign.push_back({x, own, float(dev)});
    h.delta = dev;
    h.cost = weighted(s, x, dev);
    h.star = x;
    h.star_dev = dev;
    auto raise = [&](std::uint32_t node, double d) {
        const double w = weighted(s, node, d);
        if (w > h.cost) {
            h.cost = w;
            h.star = node;
            h.star_dev = d;
        }
    };
    // The cost so far is a lower bound of the erase's cost under any view: remembered for update().
    auto remember = [&] {
        LiveNode &l = live_node(s, x);
        l.star = h.star;
        l.star_dev = float_down(h.star_dev);
        Cell &cell = s.cells[l.cell];
        cell.star_dev = std::min(cell.star_dev, l.star_dev);
        return true;
    };
    if (s.xy) {
        // A live corner's sample sits within a rounding of the float corner: a steep (sliver)
        // triangle next to it must not read more than the bound there either. Each ring node is
        // weighed once, for its steepest triangle, and only when k / OD says that could matter (the
        // margins are a few ulp): weighing every corner of every triangle took 6 % of a 4097²
        // flight's update time, and the erase at 30 fps takes 7-17 % less without it.
        std::array<double, k_max_ring> steepest;
        std::fill_n(steepest.begin(), n, 0.0);
        for (int t = 0; t < h.ntri; ++t)
            for (const std::uint8_t k : {h.tri[t].a, h.tri[t].b, h.tri[t].c})
                steepest[k] = std::max(steepest[k], h.frame[t].slope);
        for (int i = 0; i < n; ++i) {
            const double margin =
                rounding_margin(std::max(std::abs(h.p[i].x), std::abs(h.p[i].y)), steepest[i]);
            if (margin * s.weigher.upper(h.p[i]) * k_rounded_weight > h.cost)
                raise(node_of(s, h.r[i]), margin);
        }
    }
    // The node whose deviation gave this node's last cost is tried first: when it still lies under
    // the hole (then it is one of the fan's swallowed nodes: the fan tiles the hole in xy) its
    // deviation settles most evaluations that fail without walking the fan.
    const std::uint32_t last_star = live_node(s, x).star;
    if (s.xy && h.cost <= limit && last_star != x && s.record_of[last_star] >= k_absent) {
        bool inside = false;
        locate(s, h, to_glm(node_point(s, last_star)), dev, &inside);
        if (inside) {
            raise(last_star, dev);
            if (h.cost > limit)
                return remember();
        }
    }
    // Then each fan face's worst node (its list's head, see push_swallowed): one of them is most
    // often what breaks the limit, found before any list is walked.
    for (int i = 0; i < fans && h.cost <= limit; ++i) {
        const std::int32_t u = s.face_head[m.face_handle(h.h[i]).idx()];
        if (u >= 0 && std::uint32_t(u) != last_star) {
            locate(s, h, to_glm(node_point(s, std::uint32_t(u))), dev);
            raise(std::uint32_t(u), dev);
        }
    }
    if (h.cost > limit)
        return remember();
    // A scan that finds the cost over the limit goes on to k_scan_reach times the limit. Stopped
    // at the first sample over it, the scan left a cost (the node's key and lower bound) barely
    // over the limit, which the next frame's motion took back below it: the node turned candidate
    // frame after frame as the eye drew away, each time scanning its hole again.
    if (s.grid_w > 0) {
        scan_hole(s, h, pv, k_scan_reach * limit, max_swallowed);
        return remember();
    }
    for (int i = 0; i < fans && h.cost <= limit; ++i) {
        const FH f = m.face_handle(h.h[i]);
        // A node's weight is looked up only when its deviation times the largest weight where the
        // face's swallowed nodes lie (its corners' box, within their largest deviation in z) could
        // raise the cost: each update asks for fresh weights.
        const double weight_bound =
            s.xy && !s.unit_weights && s.face_head[f.idx()] >= 0
                ? swallowed_weight_bound(s, pv, h.p[i], h.p[(i + 1) % n], s.face_maxdev[f.idx()])
                : INFINITY;
        for (std::int32_t u = s.face_head[f.idx()]; u >= 0; u = s.next_swallowed[u]) {
            if (s.assign.size() > max_swallowed) {
                h.deferred = true;
                return remember();
            }
            const std::uint8_t t = locate(s, h, to_glm(node_point(s, std::uint32_t(u))), dev);
            s.assign.push_back({std::uint32_t(u), t, float(dev)});
            if (!(dev * weight_bound > h.cost))
                continue;
            raise(std::uint32_t(u), dev);
            if (h.cost > limit)
                break; // over the bound: the exact excess does not matter
        }
    }
    return remember();
}

// The queue key of the evaluated hole: its cost, or the paper's SP in the paper model.
static float key_of(const NodeEraser::Impl &s, const Hole &h) {
    if (s.options.significance.model != SpModel::paper || !s.has_view)
        return float(h.cost);
    const glm::dvec3 p = to_glm(s.mesh->point(h.v));
    NodeTerms terms;
    terms.od = glm::length(p - s.view.eye);
    terms.oa = observation_angle(s.view, p);
    terms.delta = h.delta;
    double ring_length = 0.0;
    for (int i = 0; i < h.n; ++i)
        ring_length += glm::length(h.p[i] - p);
    terms.ration = ring_length > 0.0 ? h.delta * h.n / ring_length : 0.0;
    return float(significance(terms, &s.view, s.options.significance, s.focal_distance));
}

// rank: every erasable node enters the queue keyed by the cost of its erase.
static void rank_nodes(NodeEraser::Impl &s) {
    s.heap.reset(s.nodes);
    std::vector<std::uint32_t> ranked;
    ranked.reserve(std::size_t(s.live));
    for (auto v : s.mesh->vertices()) {
        const std::uint32_t x = node_of(s, v);
        if (s.flags[x] & k_locked)
            continue;
        s.flags[x] &= std::uint8_t(~k_dirty);
        const bool erasable = evaluate(s, v, s.options.tolerance);
        s.heap.store_key(x, erasable ? key_of(s, s.hole) : INFINITY);
        if (erasable)
            ranked.push_back(x);
    }
    s.heap.build(std::move(ranked));
}

// retriangulate: replaces the fan of the evaluated hole by its new triangles in place, moves the
// swallowed nodes to the triangles that now cover them and records the erase.
static void retriangulate(NodeEraser::Impl &s) {
    Hole &h = s.hole;
    Mesh &m = *s.mesh;
    const int n = h.n;
    const int fans = h.boundary ? n - 1 : n;
    std::array<FH, k_max_ring> face;
    std::array<HH, k_max_ring> ring_he; // r_i -> r_i+1
    std::array<bool, k_max_ring> fix_out;
    for (int i = 0; i < fans; ++i) {
        face[i] = m.face_handle(h.h[i]);
        ring_he[i] = m.next_halfedge_handle(h.h[i]);
    }
    for (int i = 0; i < n; ++i)
        fix_out[i] = m.halfedge_handle(h.r[i]) == m.opposite_halfedge_handle(h.h[i]);
    HH boundary_prev, boundary_next;
    if (h.boundary) {
        boundary_prev = m.prev_halfedge_handle(m.opposite_halfedge_handle(h.h[0]));
        boundary_next = m.next_halfedge_handle(h.h[n - 1]);
    }

    // New edges re-use the spoke edges in order; a diagonal is met twice, once per side.
    struct Diagonal {
        std::uint8_t a, b;
        HH he; // a -> b
    };
    std::array<Diagonal, 2 * k_max_ring> diagonals;
    int n_diagonals = 0, next_spoke = 0;
    HH closing; // boundary: r_m -> r_0 inside the new triangle
    auto halfedge = [&](int a, int b) -> HH {
        if (b == a + 1 || (!h.boundary && a == n - 1 && b == 0))
            return ring_he[a];
        for (int k = 0; k < n_diagonals; ++k)
            if (diagonals[k].a == b && diagonals[k].b == a)
                return m.opposite_halfedge_handle(diagonals[k].he);
        const HH he = m.halfedge_handle(m.edge_handle(h.h[next_spoke++]), 0);
        m.set_vertex_handle(he, h.r[b]);
        m.set_vertex_handle(m.opposite_halfedge_handle(he), h.r[a]);
        diagonals[n_diagonals++] = {std::uint8_t(a), std::uint8_t(b), he};
        if (h.boundary && a == n - 1 && b == 0)
            closing = he;
        return he;
    };
    for (int t = 0; t < h.ntri; ++t) {
        const RingTriangle &tri = h.tri[t];
        const HH e0 = halfedge(tri.a, tri.b), e1 = halfedge(tri.b, tri.c),
                 e2 = halfedge(tri.c, tri.a);
        m.set_next_halfedge_handle(e0, e1);
        m.set_next_halfedge_handle(e1, e2);
        m.set_next_halfedge_handle(e2, e0);
        m.set_face_handle(e0, face[t]);
        m.set_face_handle(e1, face[t]);
        m.set_face_handle(e2, face[t]);
        m.set_halfedge_handle(face[t], e0);
    }
    HH new_boundary;
    if (h.boundary) {
        new_boundary = m.opposite_halfedge_handle(closing); // r_0 -> r_m
        m.set_face_handle(new_boundary, FH());
        m.set_next_halfedge_handle(boundary_prev, new_boundary);
        m.set_next_halfedge_handle(new_boundary, boundary_next);
    }
    for (int i = 0; i < n; ++i) {
        if (!fix_out[i])
            continue;
        if (h.boundary && i == 0)
            m.set_halfedge_handle(h.r[i], new_boundary);
        else if (h.boundary && i == n - 1)
            m.set_halfedge_handle(h.r[i], boundary_next);
        else
            m.set_halfedge_handle(h.r[i], ring_he[i]);
    }

    m.status(h.v).set_deleted(true);
    if (s.lattice)
        s.free_vertices.push_back(h.v);
    for (int i = next_spoke; i < n; ++i) {
        const EH e = m.edge_handle(h.h[i]);
        m.status(e).set_deleted(true);
        s.free_edges.push_back(e);
    }
    const std::uint32_t x = node_of(s, h.v);
    if (s.grid_w > 0 && s.options.shallow_history && lattice_inside(s, h) > k_kept_fan_samples) {
        KeptFan &kept = s.kept_fans[x];
        kept.head.resize(std::size_t(fans));
        kept.maxdev.resize(std::size_t(fans));
        kept.tiles.resize(std::size_t(fans));
        for (int t = 0; t < fans; ++t) {
            const std::int32_t f = face[t].idx();
            kept.head[std::size_t(t)] = s.face_head[f];
            kept.maxdev[std::size_t(t)] = s.face_maxdev[f];
            const auto tiles = s.face_tiles.find(f);
            if (tiles != s.face_tiles.end())
                kept.tiles[std::size_t(t)] = std::move(tiles->second);
            else
                kept.tiles[std::size_t(t)].clear();
        }
    }
    for (int t = 0; t < fans; ++t) {
        s.face_head[face[t].idx()] = -1;
        face_changed(s, face[t]);
        s.face_maxdev[face[t].idx()] = 0.0f;
    }
    for (int t = h.ntri; t < fans; ++t) {
        m.status(face[t]).set_deleted(true);
        s.free_faces.push_back(face[t]);
    }
    if (s.grid_w > 0) {
        for (int t = 0; t < h.ntri; ++t) {
            s.face_head[face[t].idx()] = h.tri_worst[t];
            s.face_maxdev[face[t].idx()] = h.tri_maxdev[t];
        }
    } else {
        for (const Assignment &a : s.assign)
            push_swallowed(s, face[a.triangle].idx(), a.node, a.dev);
    }
    std::array<float, k_max_ring> tri_dev;
    for (int t = 0; t < h.ntri; ++t)
        tri_dev[t] = s.face_maxdev[face[t].idx()];

    // A node erased before re-uses its record, and its ring's room in the pool when the ring
    // fits: the history stays within one record per node however long the flight.
    std::int32_t k = live_node(s, x).last_record;
    if (k < 0)
        k = std::int32_t(s.records.append(1));
    EraseRecord &record = s.records[std::size_t(k)];
    if (record.ring_capacity < n) {
        record.ring_begin = std::uint32_t(s.ring_pool.append(std::size_t(n)));
        record.ring_capacity = std::uint8_t(n);
    }
    record.ring_size = std::uint8_t(n);
    record.boundary = h.boundary;
    std::array<std::uint32_t, k_max_ring> ids;
    for (int i = 0; i < n; ++i)
        ids[i] = s.ring_pool[record.ring_begin + std::size_t(i)] = node_of(s, h.r[i]);
    remove_live(s, x, k);
    widen_fans(s, h.p.data(), ids.data(), n, h.tri.data(), tri_dev.data(), h.ntri);
    --s.live;
    s.live_faces -= fans - h.ntri;
}

// The cost an erase may reach: the tolerance less a hair that keeps float rounding inside it.
static double erase_limit(const NodeEraser::Impl &s) { return s.options.tolerance * (1.0 - 1e-6); }

// After an erase its ring nodes' keys are stale: they are marked dirty (re-evaluated when they
// reach the top of the queue) and re-enter the queue if a failed evaluation had dropped them.
static void touch_ring(NodeEraser::Impl &s) {
    const Hole &h = s.hole;
    for (int i = 0; i < h.n; ++i) {
        const std::uint32_t u = node_of(s, h.r[i]);
        if (s.flags[u] & k_locked)
            continue;
        mark_dirty(s, u);
        if (!s.heap.contains(u))
            s.heap.set(u, float(std::min<double>(s.heap.key(u), erase_limit(s))));
    }
}

// erase: pops the least significant node while its erase stays within the tolerance.
static std::int64_t erase_loop(NodeEraser::Impl &s) {
    const double tau = erase_limit(s);
    const std::int64_t budget = std::max<std::int64_t>(s.options.max_nodes, 3);
    std::int64_t erased = 0;
    while (!s.heap.empty() && s.live > budget) {
        const std::uint32_t v = s.heap.top();
        const float key = s.heap.key(v);
        if (double(key) > tau && s.options.significance.model != SpModel::paper)
            break; // every remaining key exceeds the bound (dirty keys are re-checked below)
        const bool dirty = s.flags[v] & k_dirty;
        s.flags[v] &= std::uint8_t(~k_dirty);
        // A dirty node is erased only if its cost is still the least: its evaluation stops once
        // the cost passes the next key, and it goes back with that lower bound as its key, dirty
        // (the keys stay lower bounds of the costs, so the order is the one exact keys give).
        // Half of the queue's scanning on N42E001 went to such nodes, scanned whole.
        const double second = double(s.heap.second_key());
        const bool by_cost = s.options.significance.model != SpModel::paper;
        bool erasable = evaluate(s, vh(s, v), dirty && by_cost ? std::min(tau, second) : tau);
        if (erasable && dirty && by_cost && second < tau && s.hole.cost > second) {
            if (float(s.hole.cost) > float(second)) {
                s.heap.set(v, float(s.hole.cost));
                s.flags[v] |= k_dirty;
                continue;
            }
            erasable = evaluate(s, vh(s, v), tau); // equal as floats: the exact cost decides
        }
        if (!erasable || !(s.hole.cost <= tau)) {
            s.heap.pop(); // cannot be erased now; touch_ring brings it back when its ring changes
            s.heap.store_key(v, erasable ? float(s.hole.cost) : INFINITY);
            continue;
        }
        const float fresh = key_of(s, s.hole);
        if (dirty && fresh > key && fresh > s.heap.second_key()) {
            s.heap.set(v, fresh); // its cost rose past another node's since it was ranked
            continue;
        }
        s.heap.pop();
        retriangulate(s);
        touch_ring(s);
        ++erased;
    }
    return erased;
}

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
constexpr double k_tau_rung_ratio = 8.0;
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
constexpr double k_history_rung_ratio = 1.1;
constexpr double k_history_rung_floor = 64.0; // tau / 1024 instead: the same changes per frame

static double tau_rung_ratio(const NodeEraser::Impl &s) {
    return s.options.shallow_history ? k_history_rung_ratio : k_tau_rung_ratio;
}

static int tau_rungs(const NodeEraser::Impl &s) {
    if (s.options.shallow_history)
        return int(std::ceil(std::log(k_history_rung_floor) / std::log(k_history_rung_ratio)));
    return s.grid_w > 0 ? 0 : 1;
}
constexpr double k_budget_rung_ratio = 2.0;
constexpr std::int64_t k_coarse_share = 2; // the fine rungs erase from this many times the budget
constexpr double k_fine_rung_ratio = 1.05;
// A node whose ring changed in the pass under way is not erased in it while its fan swallowed
// more nodes than this many mean shares of a live node (input nodes over live nodes at the
// pass's start; see sweep_node). A fixed 32 nodes cut the runs short once a retrieval had made
// the faces large: relative, the erase takes 11-25 % less time to 3-8 % fewer nodes at tau = 1
// px from the benchmark's low and high views (N42E001, N48W125), 8-22 % less with a node budget
// at the same or lower error, and the full grids, whose shares start at 1, are unchanged.
constexpr double k_chain_swallowed = 32.0;
// k_update_cap (decimate.hpp): three flight paths on 4097², 20 updates each, with swallowed lists:
// 65,536 -> 4,096 took 19 % off the update time for 1.0-2.6 % more TIN nodes; 1,024 took 35 % off
// for 4-16 % more nodes. With the lattice scan of a grid TIN: 16,384 costs 6 % more time than 4,096
// for 0.9-2.2 % fewer nodes.
// Node budget: the sample of first costs. Every 29th node places the first rung as well as every
// 7th did (the same output on Rainier, within 1 % on N42E001), with 3-5 % fewer evaluations.
constexpr std::uint32_t k_sample_stride = 29;

// A new sweep pass: its number in s.pass, the stamps of 256 passes ago cleared.
static void next_pass(NodeEraser::Impl &s) {
    if (++s.pass == 0) {
        if (s.node_keys)
            for (LiveNode &l : s.live_list)
                l.stamp = 0;
        else
            std::fill(s.stamp.begin(), s.stamp.end(), std::uint8_t(0));
        s.pass = 1;
    }
    s.chain_cap = std::size_t(double(k_chain_swallowed) * double(s.nodes) /
                              double(std::max<std::int64_t>(s.live, 1)));
}

// The input nodes the xy fan of x covers, estimated by its area at the input's mean density (low
// where the input does not fill its box).
static double covered_estimate(const NodeEraser::Impl &s, std::uint32_t x) {
    const Mesh &m = *s.mesh;
    const VH v = vh(s, x);
    const glm::dvec2 c(to_glm(m.point(v)));
    double twice = 0.0;
    for (const HH he : m.voh_range(v)) {
        if (m.is_boundary(he))
            continue;
        const VH a = m.to_vertex_handle(he), b = m.to_vertex_handle(m.next_halfedge_handle(he));
        twice += orient(c, glm::dvec2(to_glm(m.point(a))), glm::dvec2(to_glm(m.point(b))));
    }
    return 0.5 * twice / s.area_per_node;
}

// Leaves x as it is (not dirty, infinite key) until a change of its ring marks it dirty again.
static void park(NodeEraser::Impl &s, std::uint32_t x) {
    s.flags[x] &= std::uint8_t(~k_dirty);
    store_node_key(s, x, INFINITY);
    live_node(s, x).low_log = INFINITY;
}

// Whether the bounds an update makes carry over to the updates that follow (the screen model's, see
// Impl::face_seen_dev and LiveNode::seen_log).
static bool keeps_bounds(const NodeEraser::Impl &s) {
    return s.options.significance.model == SpModel::screen && s.updates > 0;
}

// Live node l's erase cost under the current view is at least `cost` (see LiveNode::low_log).
static void remember_low(const NodeEraser::Impl &s, LiveNode &l, double cost) {
    l.low_log = -INFINITY;
    if (keeps_bounds(s)) {
        l.low_log = float_down(std::log(cost) - 1e-6);
        l.low_at = s.updates;
    }
}

static void seen_before(NodeEraser::Impl &s, const Hole &h, std::array<double, k_max_ring> &old);
static void carry_seen(NodeEraser::Impl &s, const Hole &h,
                       const std::array<double, k_max_ring> &old);

// One step of a sweep at `limit` on live, unlocked node x: evaluates it and erases it when its
// cost is within the limit; a node whose fan swallowed more than `cap` nodes is left as it is
// until its ring changes. s.stamp holds, per node, the pass (mod 256) in which its ring last
// changed. Returns true when x was erased; x stays dirty when it must wait for the next pass.
static bool sweep_node(NodeEraser::Impl &s, std::uint32_t x, double limit,
                       std::size_t cap = std::numeric_limits<std::size_t>::max()) {
    // A node whose ring this pass changed waits for the next pass when its fan swallowed more
    // than s.chain_cap nodes (else a run of erases along a row, as on a flat sea where every cost
    // is 0, drags one growing face's nodes from erase to erase, quadratic in the run's length),
    // and always with a shallow history.
    const bool fresh = node_stamp(s, x) == s.pass;
    if (fresh && s.options.shallow_history)
        return false;
    // Over the cap by its area: left as it is without locating the first `cap` nodes (18 % of a
    // 4097² flight update's locates went to such walks). The fan lies in the disc of its reach
    // (an update keeps the live nodes' fan bounds), so most fans need no walk to pass.
    const auto over_cap = [&] {
        assert(!s.fans_stale);
        const double reach = double(live_node(s, x).reach);
        return M_PI * reach * reach > double(cap) * s.area_per_node &&
               covered_estimate(s, x) > double(cap);
    };
    if (cap != std::numeric_limits<std::size_t>::max() && s.xy && s.area_per_node > 0.0 &&
        over_cap()) {
        park(s, x);
        return false;
    }
    if (!evaluate(s, vh(s, x), limit, fresh ? std::min(cap, s.chain_cap) : cap)) {
        park(s, x);
        return false;
    }
    if (s.hole.deferred) {
        if (!fresh)
            park(s, x); // over the cap
        return false;
    }
    s.flags[x] &= std::uint8_t(~k_dirty);
    if (!(s.hole.cost <= limit)) {
        store_node_key(s, x, float(s.hole.cost));
        remember_low(s, live_node(s, x), s.hole.cost);
        return false;
    }
    s.reerased += (s.flags[x] & k_recovered) != 0;
    std::array<double, k_max_ring> seen;
    seen_before(s, s.hole, seen);
    retriangulate(s);
    carry_seen(s, s.hole, seen);
    for (int i = 0; i < s.hole.n; ++i) {
        mark_dirty(s, node_of(s, s.hole.r[i]));
        node_stamp(s, node_of(s, s.hole.r[i])) = s.pass;
    }
    return true;
}

// One pass at `limit` over the nodes of `order` (ascending ids, those that were live and not locked
// when the erase began), until `stop_at` live nodes remain. Drops from `order` the nodes it finds
// erased: a pass costs the nodes still live, not the input's. The refiner's first erase on the
// 4097² flight makes 20 passes, which each read the state of all 16.8 M ids before, 0.83 M of them
// live at first: 0.35-0.5 s of its 6.9 s (scratch runs).
static std::int64_t sweep_pass(NodeEraser::Impl &s, std::vector<std::uint32_t> &order, double limit,
                               std::int64_t stop_at, const std::function<void(double)> &report) {
    next_pass(s);
    std::int64_t erased = 0;
    std::size_t kept = 0, i = 0;
    for (; i < order.size() && s.live > stop_at; ++i) {
        if (report && i % 4096 == 0)
            report(double(i) / double(order.size()));
        const std::uint32_t x = order[i];
        if (s.record_of[x] >= 0)
            continue;
        order[kept++] = x;
        if (!(s.flags[x] & k_dirty) && double(node_key(s, x)) > limit)
            continue;
        erased += sweep_node(s, x, limit);
    }
    for (; i < order.size(); ++i)
        order[kept++] = order[i];
    order.resize(kept);
    return erased;
}

// The sweep over the nodes of `list` only, then over the rings their erases changed, at `limit`
// alone, until `stop_at` live nodes remain: its cost follows the nodes that changed (in an update,
// the full sweep's rungs below the limit cost a tenth of its erase time for no fewer nodes: N42E001
// flights at 4 frames per second). Fans over `cap` swallowed nodes are left as they are (see
// sweep_node). Returns the erases made.
static std::int64_t sweep_dirty(NodeEraser::Impl &s, double limit, std::vector<std::uint32_t> list,
                                std::size_t cap, std::int64_t stop_at = 0) {
    std::int64_t erased = 0;
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    while (!list.empty() && s.live > stop_at) {
        next_pass(s);
        std::vector<std::uint32_t> next;
        for (const std::uint32_t x : list) {
            if (s.live <= stop_at)
                break;
            if ((s.flags[x] & k_locked) || s.record_of[x] >= 0)
                continue;
            if (!(s.flags[x] & k_dirty) && double(node_key(s, x)) > limit)
                continue;
            if (sweep_node(s, x, limit, cap)) {
                ++erased;
                for (int i = 0; i < s.hole.n; ++i)
                    next.push_back(node_of(s, s.hole.r[i]));
            } else if (s.flags[x] & k_dirty) {
                next.push_back(x); // waits for the next pass
            }
        }
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        list = std::move(next);
    }
    return erased;
}

// The fine rungs of a node budget, until `budget` live nodes remain or a rung reaches `tau`: the
// first at `limit` (it finishes the coarse rung the budget's first stop cut short), each next one
// k_fine_rung_ratio above the last, or at the least key above it when that is higher. A rung sweeps
// the dirty nodes and those whose key it covers, then the rings their erases change, until none is
// left: afterwards every live node's key (a lower bound of its cost) is above the rung. Returns the
// erases made.
static std::int64_t fine_rungs(NodeEraser::Impl &s, double limit, double tau, std::int64_t budget,
                               const std::function<void()> &report) {
    std::int64_t erased = 0;
    limit = std::min(limit, tau);
    while (s.live > budget) {
        if (report)
            report();
        std::vector<std::uint32_t> list;
        for (const LiveNode &l : s.live_list)
            if (!(s.flags[l.node] & k_locked) &&
                ((s.flags[l.node] & k_dirty) || double(node_key(s, l)) <= limit))
                list.push_back(l.node);
        erased +=
            sweep_dirty(s, limit, std::move(list), std::numeric_limits<std::size_t>::max(), budget);
        if (limit >= tau)
            break;
        double least = INFINITY;
        for (const LiveNode &l : s.live_list)
            if (!(s.flags[l.node] & k_locked))
                least = std::min(least, double(node_key(s, l)));
        if (!(least < INFINITY))
            break; // no live node can be erased
        limit = std::min(tau, std::max(limit * k_fine_rung_ratio, least));
    }
    return erased;
}

// classify -> erase: SP models whose key is the cost (not `paper`), see the sweep above.
static std::int64_t sweep_erase(NodeEraser::Impl &s) {
    const double tau = erase_limit(s);
    s.heap.reset(s.nodes); // keys only: 0 until a node is first measured
    for (auto v : s.mesh->vertices())
        s.flags[node_of(s, v)] &= std::uint8_t(~k_dirty);
    std::vector<std::uint32_t> order;
    order.reserve(std::size_t(s.live));
    for (std::uint32_t x = 0; x < s.nodes; ++x)
        if (!(s.flags[x] & k_locked) && s.record_of[x] < 0)
            order.push_back(x);
    const std::function<void(double)> &progress = s.options.progress;
    const std::int64_t budget = std::max<std::int64_t>(s.options.max_nodes, 3);
    const std::int64_t first_live = s.live;
    // Progress: with a budget, the erases made over those it needs; with a bound alone, pass k
    // (from 0) spans [1 - 0.1^k, 1 - 0.1^(k+1)).
    double pass_share = 1.0;
    const auto by_erases = [&] {
        progress(
            first_live > budget
                ? std::clamp(double(first_live - s.live) / double(first_live - budget), 0.0, 1.0)
                : 1.0);
    };
    const auto report = [&](double within) {
        if (s.options.max_nodes > 0)
            by_erases();
        else
            progress(1.0 - pass_share + 0.9 * pass_share * within);
    };
    auto sweep = [&](double limit, std::int64_t stop_at) {
        const std::int64_t made = sweep_pass(
            s, order, limit, stop_at, progress ? std::function<void(double)>(report) : nullptr);
        pass_share *= 0.1;
        return made;
    };
    std::int64_t erased = 0;
    if (s.options.max_nodes <= 0) {
        for (int rung = tau_rungs(s); rung > 0; --rung)
            erased += sweep(tau * std::pow(tau_rung_ratio(s), -rung), 0);
        for (std::int64_t made = 1; made > 0;) {
            made = sweep(tau, 0);
            erased += made;
        }
        return erased;
    }
    const std::int64_t far = k_coarse_share * budget;
    double limit = 0.0; // the last rung's
    if (s.live > far) {
        // The first rung: at least live - far erases are needed before the fine rungs, and an erase
        // rarely costs less than the node's cost on the input, so the (live - far)-th smallest
        // first cost (estimated on every k_sample_stride-th node) is about the least bound the
        // output can reach; rungs below it only add passes.
        std::vector<float> costs;
        for (std::uint32_t x = 0; x < s.nodes; x += k_sample_stride) {
            if ((s.flags[x] & k_locked) || s.record_of[x] >= 0)
                continue;
            const float cost = evaluate(s, vh(s, x), INFINITY) ? float(s.hole.cost) : INFINITY;
            s.heap.store_key(x, cost);
            costs.push_back(cost);
        }
        const auto nth = costs.begin() + std::ptrdiff_t(double(costs.size()) *
                                                        double(s.live - far) / double(s.live));
        if (nth != costs.end()) {
            std::nth_element(costs.begin(), nth, costs.end());
            double highest = 0.0;
            for (const float c : costs)
                if (std::isfinite(c))
                    highest = std::max(highest, double(c));
            for (limit = std::max(double(*nth), 1e-30);
                 s.live > far && limit < tau && limit <= 2.0 * highest;
                 limit *= k_budget_rung_ratio)
                erased += sweep(limit, far);
            limit /= k_budget_rung_ratio;
        }
    }
    return erased +
           fine_rungs(s, limit, tau, budget, progress ? std::function<void()>(by_erases) : nullptr);
}

// ---- Recovery ----------------------------------------------------------------------------------

// A free edge for a re-insert: one an erase freed, or a new one once compact() dropped them.
static EH take_edge(NodeEraser::Impl &s) {
    if (s.free_edges.empty())
        return s.mesh->edge_handle(s.mesh->new_edge(VH(), VH()));
    const EH e = s.free_edges.back();
    s.free_edges.pop_back();
    return e;
}

static FH take_face(NodeEraser::Impl &s) {
    if (s.free_faces.empty()) {
        s.face_head.push_back(-1);
        s.face_blocked.push_back(0);
        s.face_maxdev.push_back(0.0f);
        s.face_seen_dev.push_back(-1.0f);
        s.face_seen.push_back(0);
        return s.mesh->new_face();
    }
    const FH f = s.free_faces.back();
    s.free_faces.pop_back();
    return f;
}

// The vertex of erased node x: its own without a lattice, else one an erase freed or a new one,
// given x's point and sample (marked deleted, without edges, as erased nodes are).
static VH vertex_for(NodeEraser::Impl &s, std::uint32_t x) {
    if (!s.lattice)
        return VH(int(x));
    Mesh &m = *s.mesh;
    VH v;
    if (s.free_vertices.empty()) {
        v = m.add_vertex(node_point(s, x));
        m.status(v).set_deleted(true);
        s.sample_of.push_back(x);
    } else {
        v = s.free_vertices.back();
        s.free_vertices.pop_back();
        m.point(v) = node_point(s, x);
        s.sample_of[std::size_t(v.idx())] = x;
    }
    m.property(s.origin, v) = std::int64_t(x);
    return v;
}

// Re-inserts erased node x, whose ring nodes are all live: the faces inside its ring become its
// fan again, the diagonals and two free edges its spokes.
static void reinsert(NodeEraser::Impl &s, std::uint32_t x) {
    Mesh &m = *s.mesh;
    std::array<std::uint32_t, 4> scratch;
    const ErasedRing erased = erased_ring(s, x, scratch);
    const int n = erased.size;
    const bool boundary = erased.boundary;
    const std::uint32_t *ring = erased.nodes;
    const VH v = vertex_for(s, x);
    auto ring_index = [&](VH u) {
        const std::uint32_t id = node_of(s, u);
        for (int i = 0; i < n; ++i)
            if (ring[i] == id)
                return i;
        return -1;
    };

    // The hole's faces, found by a walk across diagonals from the ring edge r_0 -> r_1.
    std::array<FH, k_max_ring> face;
    std::array<HH, k_max_ring> ring_he;
    std::array<EH, k_max_ring> spoke_edge;
    int n_faces = 0, n_edges = 0;
    HH closing;
    face[n_faces++] = m.face_handle(find_halfedge(m, vh(s, ring[0]), vh(s, ring[1])));
    for (int k = 0; k < n_faces; ++k) {
        HH he = m.halfedge_handle(face[k]);
        for (int c = 0; c < 3; ++c, he = m.next_halfedge_handle(he)) {
            const int a = ring_index(m.from_vertex_handle(he)),
                      b = ring_index(m.to_vertex_handle(he));
            assert(a >= 0 && b >= 0);
            if (b == a + 1 || (!boundary && a == n - 1 && b == 0)) {
                ring_he[a] = he;
                continue;
            }
            if (boundary && a == n - 1 && b == 0) {
                closing = he;
                spoke_edge[n_edges++] = m.edge_handle(he);
                continue;
            }
            if (a < b)
                spoke_edge[n_edges++] = m.edge_handle(he); // a diagonal, counted from one side
            const FH across = m.opposite_face_handle(he);
            if (std::find(face.begin(), face.begin() + n_faces, across) == face.begin() + n_faces)
                face[n_faces++] = across;
        }
    }
    assert(n_faces == n - 2);
    // x is under a face outside its ring when a recovery filed it there (see Impl::swallowed_by):
    // left in that list, the live node would be taken for an erased one (its recovery, its next
    // erase's list).
    if (s.grid_w == 0) {
        const std::int32_t by = s.swallowed_by[x];
        if (std::none_of(face.begin(), face.begin() + n_faces, [&](FH f) { return f.idx() == by; }))
            unlink_swallowed(s, by, x);
    }

    std::vector<std::uint32_t> &swallowed = s.swallowed_scratch;
    const std::size_t swallowed_begin = swallowed.size();
    for (int k = 0; k < n_faces; ++k) {
        if (s.grid_w == 0)
            for (std::int32_t u = s.face_head[face[k].idx()]; u >= 0; u = s.next_swallowed[u])
                if (std::uint32_t(u) != x)
                    swallowed.push_back(std::uint32_t(u));
        s.face_head[face[k].idx()] = -1;
        face_changed(s, face[k]);
        s.face_maxdev[face[k].idx()] = 0.0f;
    }

    HH boundary_prev, boundary_next, old_boundary;
    if (boundary) {
        old_boundary = m.opposite_halfedge_handle(closing); // r_0 -> r_m
        boundary_prev = m.prev_halfedge_handle(old_boundary);
        boundary_next = m.next_halfedge_handle(old_boundary);
    }
    std::array<bool, k_max_ring> fix_out;
    for (int i = 0; i < n; ++i) {
        const EH out = m.edge_handle(m.halfedge_handle(vh(s, ring[i])));
        fix_out[i] = false;
        for (int k = 0; k < n_edges; ++k)
            fix_out[i] |= spoke_edge[k] == out;
    }
    while (n_edges < n)
        spoke_edge[n_edges++] = take_edge(s);
    const int fans = boundary ? n - 1 : n;
    while (n_faces < fans)
        face[n_faces++] = take_face(s);

    std::array<HH, k_max_ring> spoke; // x -> r_i
    for (int i = 0; i < n; ++i) {
        spoke[i] = m.halfedge_handle(spoke_edge[i], 0);
        m.set_vertex_handle(spoke[i], vh(s, ring[i]));
        m.set_vertex_handle(m.opposite_halfedge_handle(spoke[i]), v);
        m.status(spoke_edge[i]).set_deleted(false);
    }
    for (int i = 0; i < fans; ++i) {
        const HH back = m.opposite_halfedge_handle(spoke[(i + 1) % n]);
        m.set_next_halfedge_handle(spoke[i], ring_he[i]);
        m.set_next_halfedge_handle(ring_he[i], back);
        m.set_next_halfedge_handle(back, spoke[i]);
        m.set_face_handle(spoke[i], face[i]);
        m.set_face_handle(ring_he[i], face[i]);
        m.set_face_handle(back, face[i]);
        m.set_halfedge_handle(face[i], spoke[i]);
        m.status(face[i]).set_deleted(false);
    }
    if (boundary) {
        const HH in = m.opposite_halfedge_handle(spoke[0]); // r_0 -> x
        m.set_face_handle(in, FH());
        m.set_face_handle(spoke[n - 1], FH());
        m.set_next_halfedge_handle(boundary_prev, in);
        m.set_next_halfedge_handle(in, spoke[n - 1]);
        m.set_next_halfedge_handle(spoke[n - 1], boundary_next);
        m.set_halfedge_handle(v, spoke[n - 1]);
    } else {
        m.set_halfedge_handle(v, spoke[0]);
    }
    for (int i = 0; i < n; ++i) {
        if (!fix_out[i])
            continue;
        if (boundary && i == 0)
            m.set_halfedge_handle(vh(s, ring[i]), m.opposite_halfedge_handle(spoke[0]));
        else if (boundary && i == n - 1)
            m.set_halfedge_handle(vh(s, ring[i]), boundary_next);
        else
            m.set_halfedge_handle(vh(s, ring[i]), ring_he[i]);
    }
    m.status(v).set_deleted(false);
    if (s.flags[x] & k_unread) {
        s.flags[x] &= std::uint8_t(~k_unread);
        ++s.entered;
    }

    // Swallowed nodes go back to the fan face that covers them.
    Hole &h = s.hole;
    h.v = v;
    h.n = n + 1;
    h.boundary = boundary;
    const glm::dvec3 pv = to_glm(m.point(v));
    for (int i = 0; i < n; ++i)
        h.p[i] = to_glm(m.point(vh(s, ring[i])));
    h.p[n] = pv;
    if (s.xy) {
        h.origin = glm::dvec3(0.0);
        h.ex = {1, 0, 0};
        h.ey = {0, 1, 0};
    } else {
        glm::dvec3 normal(0.0);
        for (int i = 0; i < fans; ++i)
            normal += glm::cross(h.p[i] - pv, h.p[(i + 1) % n] - pv);
        const glm::dvec3 ez = glm::normalize(normal);
        const glm::dvec3 helper = std::abs(ez.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        h.origin = pv;
        h.ex = glm::normalize(glm::cross(helper, ez));
        h.ey = glm::cross(ez, h.ex);
    }
    for (int i = 0; i <= n; ++i)
        h.q[i] = project(h, h.p[i]);
    h.ntri = fans;
    for (int i = 0; i < fans; ++i)
        h.tri[i] = {std::uint8_t(n), std::uint8_t(i), std::uint8_t((i + 1) % n)};
    frame_triangles(s, h);
    if (const auto kept = s.kept_fans.find(x); kept != s.kept_fans.end()) {
        // The fan's faces are the triangles they were at the erase, holding the same samples.
        for (int i = 0; i < fans; ++i) {
            const std::int32_t f = face[i].idx();
            s.face_head[f] = kept->second.head[std::size_t(i)];
            s.face_maxdev[f] = kept->second.maxdev[std::size_t(i)];
            if (!kept->second.tiles[std::size_t(i)].empty()) {
                s.face_tiles[f] = std::move(kept->second.tiles[std::size_t(i)]);
                s.face_blocked[f] = 1;
            }
        }
        s.kept_fans.erase(kept);
        ++s.fans_kept;
    } else if (s.grid_w > 0) {
        for (int i = 0; i < fans; ++i) {
            const std::uint32_t a = ring[i], b = ring[(i + 1) % n];
            const auto [maxdev, worst] =
                face_worst(s, x, a, b, h.frame[i], pv, h.p[i], h.p[(i + 1) % n]);
            s.face_head[face[i].idx()] = worst;
            s.face_maxdev[face[i].idx()] = maxdev;
        }
    }
    for (std::size_t k = swallowed_begin; k < swallowed.size(); ++k) {
        const std::uint32_t u = swallowed[k];
        double dev = 0.0;
        const FH f = face[locate(s, h, to_glm(node_point(s, u)), dev)];
        push_swallowed(s, f.idx(), u, float(dev));
    }
    swallowed.resize(swallowed_begin);
    add_live(s, x, s.record_of[x] == k_regular_ring ? -1 : s.record_of[x], v);
    // Its key from before its erase says nothing of the fan it has now (an infinite one kept the
    // update's pick from ever re-evaluating it).
    if (s.node_keys || s.heap.has_key(x))
        store_node_key(s, x, 0.0f);
    std::array<float, k_max_ring> tri_dev;
    for (int i = 0; i < fans; ++i)
        tri_dev[i] = s.face_maxdev[face[i].idx()];
    std::array<std::uint32_t, k_max_ring + 1> ids;
    std::copy(ring, ring + n, ids.begin());
    ids[n] = x;
    widen_fans(s, h.p.data(), ids.data(), n + 1, h.tri.data(), tri_dev.data(), fans);
    ++s.live;
    s.live_faces += fans - (n - 2);
}

// ---- NodeEraser --------------------------------------------------------------------------------

// Live nodes per cell of the update's grid. The grid follows the live nodes, not the input: each
// update passes twice over the cells, and with cells of 1024 input nodes (16 k cells for the 43 k
// live nodes of a 4097² flight) those passes cost as much as the walks over the nodes. At 30 frames
// per second with the camera 8 times slower than the flight benchmark's paths, a frame's median
// took 19-24 % less with 64 live nodes per cell than with 1024 input nodes (scratch runs on the
// fly-over: 20 to 1,400 live nodes per cell were within 13 % of each other, 80 to 1,400 within
// 5 %).
constexpr double k_live_per_cell = 64.0;
// The grid is sized again once the live nodes are this many times more, or fewer, than it was for.
constexpr std::int64_t k_regrid_ratio = 4;

// Sizes the update's grid for s.live live nodes over the input's extent, at most ~4000 cells a side
// however thin the outline, and puts the live nodes in its cells. The cells' fan bounds are their
// nodes' (rebuild_fans makes them when the nodes' are stale); their star bounds and dirty flags are
// the conservative ones, so the next update visits every cell once.
static void regrid(NodeEraser::Impl &s) {
    const glm::dvec2 extent = s.grid_hi - s.grid_lo;
    const double cells = std::max(1.0, double(s.live) / k_live_per_cell);
    const double area = extent.x * extent.y;
    s.cell_side = std::max(
        {area > 0.0 ? std::sqrt(area / cells) : 0.0, std::max(extent.x, extent.y) / 4000.0, 1e-30});
    s.grid_nx = int(extent.x / s.cell_side) + 1;
    s.grid_ny = int(extent.y / s.cell_side) + 1;
    s.grid_live = s.live;
    s.cells.assign(std::size_t(s.grid_nx) * std::size_t(s.grid_ny), Cell{});
    for (LiveNode &l : s.live_list) {
        const glm::dvec3 p = to_glm(l.p);
        l.cell = cell_of(s, p);
        Cell &cell = s.cells[l.cell];
        cell.zlo = std::min(cell.zlo, float_down(p.z));
        cell.zhi = std::max(cell.zhi, float_up(p.z));
        cell.fan_dev = std::max(cell.fan_dev, l.fan_dev);
        cell.reach = std::max(cell.reach, l.reach);
    }
}

// The arrays an update reads at random, one entry per node (or edge, face), on huge pages: on a
// 4097² grid they span hundreds of MB, and with 4 KiB pages most reads miss the TLB. The flight
// benchmark's updates ran 10 % faster. Only for a refiner's mesh (see rebind): a single erase of
// N42E001 gained nothing, as the collapse into huge pages costs what the erase saves.
// The mesh's arrays move when they grow past their reserved room (a sparse lattice's vertices as
// samples enter, edges and faces as the TIN grows): update() advises them again then (see
// Impl::advised). The heightfield of a sparse lattice, which its scans read, is advised too.
// Without it the 4097² flights' frames ran 3-28 % slower than with every sample a vertex.
static void advise_huge(NodeEraser::Impl &s) {
    const Mesh &m = *s.mesh;
    s.advised = {m.n_vertices() > 0 ? m.points() : nullptr,
                 m.n_edges() > 0 ? &m.edge(EH(0)) : nullptr,
                 m.n_faces() > 0 ? &m.face(FH(0)) : nullptr};
    if (m.n_vertices() > 0) {
        // Over the reserved room: the vertices that enter fill it.
        const std::size_t room = m.property(m.points_pph()).data_vector().capacity();
        advise_huge_pages(m.points(), room * sizeof(Mesh::Point));
        advise_huge_pages(&m.vertex(VH(0)), room * sizeof(m.vertex(VH(0))));
        advise_huge_pages(&m.status(VH(0)), room * sizeof(m.status(VH(0))));
    }
    if (m.n_edges() > 0)
        advise_huge_pages(&m.edge(EH(0)), m.n_edges() * sizeof(m.edge(EH(0))));
    if (m.n_faces() > 0)
        advise_huge_pages(&m.face(FH(0)), m.n_faces() * sizeof(m.face(FH(0))));
    if (s.lattice)
        advise_huge_pages(s.lattice->z.data(), s.lattice->z.size() * sizeof(float));
    const auto whole = [](const auto &v) { advise_huge_pages(v.data(), v.size() * sizeof(v[0])); };
    whole(s.record_of);
    whole(s.sample_of);
    whole(s.flags);
    whole(s.stamp);
    whole(s.weight);
    whole(s.next_swallowed);
    whole(s.face_head);
    whole(s.face_maxdev);
}

// A grid TIN that holds only some of its lattice's samples (a retrieval's): the faces swallowed the
// others from the start, so each face gets its worst sample and deviation, and its corners' fan
// bounds, as an erase would have left them.
static void swallow_absent(NodeEraser::Impl &s) {
    const Mesh &m = *s.mesh;
    for (auto f : m.faces()) {
        const HH he = m.halfedge_handle(f);
        const std::array<std::uint32_t, 3> ids = {
            node_of(s, m.from_vertex_handle(he)), node_of(s, m.to_vertex_handle(he)),
            node_of(s, m.to_vertex_handle(m.next_halfedge_handle(he)))};
        std::array<glm::dvec3, 3> p;
        for (int k = 0; k < 3; ++k)
            p[k] = to_glm(node_point(s, ids[k]));
        const TriangleFrame frame = triangle_frame(glm::dvec2(p[0]), glm::dvec2(p[1]),
                                                   glm::dvec2(p[2]), true, p[0].z, p[1].z, p[2].z);
        const auto [maxdev, worst] = face_worst(s, ids[0], ids[1], ids[2], frame, p[0], p[1], p[2]);
        s.face_head[f.idx()] = worst;
        s.face_maxdev[f.idx()] = maxdev;
        constexpr RingTriangle corners{0, 1, 2};
        if (worst >= 0)
            widen_fans(s, p.data(), ids.data(), 3, &corners, &maxdev, 1);
    }
}

NodeEraser::NodeEraser(Mesh &mesh, const View *view, const EraseOptions &options)
    : impl_(std::make_unique<Impl>()) {
    Impl &s = *impl_;
    s.mesh = &mesh;
    assert(s.mesh->is_trimesh());
    std::int64_t absent = 0;
    for (auto v : s.mesh->all_vertices())
        if (s.mesh->status(v).deleted()) {
            if (s.mesh->halfedge_handle(v).is_valid())
                throw std::invalid_argument("NodeEraser: a deleted vertex still has edges");
            ++absent;
        }
    s.nodes = std::uint32_t(s.mesh->n_vertices());
    std::vector<std::int32_t> vertex_of; // a sparse lattice's, while the constructor runs
    if (options.lattice) {
        const Heightfield &hf = *options.lattice;
        if (absent > 0)
            throw std::invalid_argument("NodeEraser: a sparse lattice TIN with deleted vertices");
        s.origin = find_origin_property(*s.mesh);
        if (!s.origin.is_valid())
            throw std::invalid_argument("NodeEraser: a sparse lattice TIN without its samples");
        s.lattice = &hf;
        s.nodes = std::uint32_t(hf.size());
        s.inverse_width = 1.0 / double(hf.width);
        s.lattice_x.resize(std::size_t(hf.width));
        s.lattice_y.resize(std::size_t(hf.height));
        for (int c = 0; c < hf.width; ++c)
            s.lattice_x[std::size_t(c)] = grid_point(hf, c, 0)[0];
        for (int r = 0; r < hf.height; ++r)
            s.lattice_y[std::size_t(r)] = grid_point(hf, 0, r)[1];
        vertex_of.assign(s.nodes, -1);
        s.sample_of.resize(s.mesh->n_vertices());
        for (auto v : s.mesh->vertices()) {
            const std::int64_t x = s.mesh->property(s.origin, v);
            if (x < 0 || x >= hf.size() || vertex_of[std::size_t(x)] >= 0 ||
                s.mesh->point(v) != node_point(s, std::uint32_t(x)))
                throw std::invalid_argument("NodeEraser: a sparse lattice TIN's vertex is not "
                                            "its sample");
            vertex_of[std::size_t(x)] = v.idx();
            s.sample_of[std::size_t(v.idx())] = std::uint32_t(x);
        }
        absent = std::int64_t(s.nodes) - std::int64_t(s.mesh->n_vertices());
    }
    s.live = std::int64_t(s.nodes) - absent;
    s.live_faces = std::int64_t(s.mesh->n_faces());
    bool all_ccw = true;
    for (auto f : s.mesh->faces()) {
        auto he = s.mesh->halfedge_handle(f);
        const auto &a = s.mesh->point(s.mesh->from_vertex_handle(he));
        const auto &b = s.mesh->point(s.mesh->to_vertex_handle(he));
        const auto &c = s.mesh->point(s.mesh->to_vertex_handle(s.mesh->next_halfedge_handle(he)));
        if (orient({a[0], a[1]}, {b[0], b[1]}, {c[0], c[1]}) <= 0.0) {
            all_ccw = false;
            break;
        }
    }
    s.xy = options.projection == Projection::xy ||
           (options.projection == Projection::automatic && all_ccw);
    s.grid_w = !s.xy ? 0 : s.lattice ? std::uint32_t(s.lattice->width) : grid_width(*s.mesh);
    if (s.lattice && s.grid_w == 0)
        throw std::invalid_argument("NodeEraser: a sparse lattice TIN is not counter-clockwise");
    if (absent > 0 && s.grid_w == 0)
        throw std::invalid_argument(
            "NodeEraser: deleted vertices in a mesh that is not a grid TIN");
    if (s.grid_w == 0) {
        s.next_swallowed.assign(s.nodes, -1);
        s.swallowed_by.assign(s.nodes, -1);
    }
    s.face_head.assign(s.mesh->n_faces(), -1);
    s.face_blocked.assign(s.mesh->n_faces(), 0);
    s.face_maxdev.assign(s.mesh->n_faces(), 0.0f);
    s.face_seen_dev.assign(s.mesh->n_faces(), -1.0f);
    s.face_seen.assign(s.mesh->n_faces(), 0);
    s.record_of.resize(s.nodes);
    s.live_list.reserve(std::size_t(s.live));
    // The update's grid, over the input's extent, sized for its live nodes.
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    for (auto v : s.mesh->vertices()) {
        const glm::dvec3 p = to_glm(s.mesh->point(v));
        lo = glm::min(lo, glm::dvec2(p));
        hi = glm::max(hi, glm::dvec2(p));
    }
    if (s.nodes > 0) {
        const glm::dvec2 extent = hi - lo;
        s.area_per_node = extent.x * extent.y / double(s.nodes);
        s.grid_lo = lo;
        s.grid_hi = hi;
    }
    regrid(s);
    for (std::uint32_t x = 0; x < s.nodes; ++x) {
        const VH v = s.lattice ? VH(vertex_of[x]) : VH(int(x));
        if (!v.is_valid() || s.mesh->status(v).deleted())
            s.record_of[x] = k_absent;
        else
            add_live(s, x, -1, v);
    }
    std::vector<std::int32_t>().swap(vertex_of);
    s.absent_for_good = absent > 0 && !options.absent_history;
    if (absent > 0 && options.absent_history) {
        s.flags.assign(s.nodes, 0);
        const auto height = s.nodes / s.grid_w;
        s.regular = std::make_unique<RegularRings>(s.grid_w, height);
        if (options.retrieval_tin && RegularRings::regular_for_retrievals(s.grid_w, height)) {
            for (std::size_t x = 0; x < s.record_of.size(); ++x)
                if (s.record_of[x] == k_absent) {
                    s.flags[x] = k_unread;
                    s.record_of[x] = k_regular_ring;
                }
        } else {
            absent_sample_rings(
                *s.mesh, s.grid_w, height, s.sample_of,
                [&](std::uint32_t x, const std::uint32_t *ring, int n, bool boundary) {
                    s.flags[x] = k_unread;
                    std::array<std::uint32_t, 4> regular;
                    bool chain = false;
                    if (s.regular->ring(x, regular.data(), chain) == n && chain == boundary &&
                        std::equal(ring, ring + n, regular.data())) {
                        s.record_of[x] = k_regular_ring;
                        return;
                    }
                    const std::size_t k = s.records.append(1);
                    EraseRecord &record = s.records[k];
                    record.ring_begin = std::uint32_t(s.ring_pool.append(std::size_t(n)));
                    record.ring_size = record.ring_capacity = std::uint8_t(n);
                    record.boundary = boundary;
                    std::copy(ring, ring + n, &s.ring_pool[record.ring_begin]);
                    s.record_of[x] = std::int32_t(k);
                });
        }
    }
    if (absent > 0)
        swallow_absent(s);
    set_view(view, options);
}

// Drops every live node's seen and low bounds (their keys may have changed without them).
static void forget_nodes(NodeEraser::Impl &s) {
    for (LiveNode &l : s.live_list) {
        l.seen_log = INFINITY;
        l.low_log = -INFINITY;
    }
}

NodeEraser::~NodeEraser() = default;
NodeEraser::NodeEraser(NodeEraser &&) noexcept = default;
NodeEraser &NodeEraser::operator=(NodeEraser &&) noexcept = default;

void NodeEraser::set_view(const View *view, const EraseOptions &options) {
    Impl &s = *impl_;
    assert(view || options.significance.model == SpModel::vertical);
    s.options = options;
    s.has_view = view != nullptr;
    std::fill(s.face_seen_dev.begin(), s.face_seen_dev.end(), -1.0f); // the model may change
    forget_nodes(s);
    if (view) {
        s.view = *view;
        if (options.significance.model == SpModel::paper)
            s.focal_distance = std::max(focal_point(*s.mesh, *view).distance, 1e-9);
    }
    classify_nodes(s);
}

EraseStats NodeEraser::erase() {
    Impl &s = *impl_;
    s.fans_stale = true;
    Stopwatch clock;
    EraseStats stats;
    stats.input_nodes = s.live;
    stats.input_triangles = s.live_faces;
    const std::int64_t evaluations = s.evaluations;
    if (s.node_keys) { // back to the per-vertex keys (reset below) and stamps
        s.stamp.assign(s.nodes, 0);
        for (const LiveNode &l : s.live_list)
            s.stamp[l.node] = l.stamp;
        s.node_keys = false;
    }
    if (s.options.significance.model != SpModel::paper &&
        (s.options.max_nodes > 0 || std::isfinite(s.options.tolerance))) {
        stats.erased = sweep_erase(s);
    } else {
        rank_nodes(s);
        stats.erased = erase_loop(s);
    }
    if (s.live_list.capacity() > 2 * s.live_list.size())
        s.live_list.shrink_to_fit(); // an update keeps the live nodes only
    forget_nodes(s);
    const EraseStats now = measure();
    stats.output_nodes = s.live;
    stats.output_triangles = s.live_faces;
    stats.evaluations = s.evaluations - evaluations;
    stats.max_weighted = now.max_weighted;
    stats.max_screen_px = now.max_screen_px;
    stats.max_vertical = now.max_vertical;
    stats.ms = clock.ms();
    return stats;
}

// Recovers x and the erases it depends on; appends every node re-inserted to `done`.
static std::int64_t recover_closure(NodeEraser::Impl &s, std::uint32_t v,
                                    std::vector<std::uint32_t> *done) {
    std::int64_t recovered = 0;
    std::vector<std::uint32_t> stack{v};
    while (!stack.empty()) {
        const std::uint32_t x = stack.back();
        if (s.record_of[x] < 0) {
            stack.pop_back();
            continue;
        }
        std::array<std::uint32_t, 4> scratch;
        const ErasedRing ring = erased_ring(s, x, scratch);
        bool ready = true;
        for (int i = 0; i < ring.size; ++i) {
            const std::uint32_t u = ring.nodes[i];
            if (s.record_of[u] >= 0) {
                stack.push_back(u); // erased after x and over x's triangles: undo it first
                ready = false;
            }
        }
        if (!ready)
            continue;
        reinsert(s, x);
        if (done)
            done->push_back(x);
        stack.pop_back();
        ++recovered;
    }
    return recovered;
}

std::int64_t NodeEraser::recover(Mesh::VertexHandle v) {
    return recover_closure(*impl_, node_of(*impl_, v), nullptr);
}

std::int64_t NodeEraser::recover_all() {
    Impl &s = *impl_;
    // The records from the last made to the first (a one-off erase undone in reverse: no closure
    // to walk).
    std::vector<std::pair<std::int32_t, std::uint32_t>> erased;
    for (std::uint32_t x = 0; x < std::uint32_t(s.record_of.size()); ++x)
        if (s.record_of[x] >= 0)
            erased.emplace_back(s.record_of[x], x);
    std::sort(erased.begin(), erased.end(), std::greater<>());
    std::int64_t recovered = 0;
    for (const auto &[record, x] : erased)
        recovered += recover_closure(s, x, nullptr);
    return recovered;
}

bool NodeEraser::is_erased(Mesh::VertexHandle v) const {
    return impl_->record_of[node_of(*impl_, v)] >= 0;
}

ErasedNodeRing NodeEraser::ring(Mesh::VertexHandle v) const {
    assert(is_erased(v));
    std::array<std::uint32_t, 4> scratch;
    const ErasedRing ring = erased_ring(*impl_, node_of(*impl_, v), scratch);
    return {{ring.nodes, ring.nodes + ring.size}, ring.boundary};
}

void NodeEraser::compact() {
    Impl &s = *impl_;
    Mesh &m = *s.mesh;
    // The per-face state rides along as face properties while the collection moves the faces.
    OpenMesh::FPropHandleT<float> maxdev;
    OpenMesh::FPropHandleT<std::int32_t> head;
    m.add_property(maxdev);
    m.add_property(head);
    m.property(maxdev).data_vector() = std::move(s.face_maxdev);
    m.property(head).data_vector() = std::move(s.face_head);
    // A sparse lattice's erased vertices go too (its erased nodes have none): each live node's
    // vertex is found again from the origin property, which the collection moves with it.
    m.garbage_collection(s.lattice != nullptr, true, true);
    if (s.lattice) {
        std::vector<VH>().swap(s.free_vertices);
        s.sample_of.resize(m.n_vertices());
        s.sample_of.shrink_to_fit();
        for (auto v : m.vertices()) {
            const std::uint32_t x = std::uint32_t(m.property(s.origin, v));
            s.sample_of[std::size_t(v.idx())] = x;
            live_node(s, x).vertex = v.idx();
        }
    }
    s.face_maxdev = std::move(m.property(maxdev).data_vector());
    s.face_head = std::move(m.property(head).data_vector());
    for (std::size_t f = 0; f < s.face_head.size() && s.grid_w == 0; ++f)
        for (std::int32_t u = s.face_head[f]; u >= 0; u = s.next_swallowed[std::size_t(u)])
            s.swallowed_by[std::size_t(u)] = std::int32_t(f); // the faces moved
    m.remove_property(maxdev);
    m.remove_property(head);
    s.face_maxdev.shrink_to_fit();
    s.face_head.shrink_to_fit();
    // The blocks name faces by index: they go (the next scans build them again).
    s.face_blocked.assign(s.face_head.size(), 0);
    s.face_blocked.shrink_to_fit();
    s.face_seen_dev.assign(s.face_head.size(), -1.0f);
    s.face_seen_dev.shrink_to_fit();
    s.face_seen.assign(s.face_head.size(), 0);
    s.face_seen.shrink_to_fit();
    s.face_blocks.clear();
    s.face_tiles.clear();
    for (LiveNode &l : s.live_list) {
        l.key = s.heap.key(l.node);
        l.stamp = s.stamp[l.node];
    }
    s.heap.release();
    std::vector<std::uint8_t>().swap(s.stamp);
    s.node_keys = true;
    std::vector<float>().swap(s.weight); // and compute weights where they need them
    std::vector<EH>().swap(s.free_edges);
    std::vector<FH>().swap(s.free_faces);
    s.records.shrink_to_fit();
    s.ring_pool.shrink_to_fit();
}

static void rebuild_fans(NodeEraser::Impl &s);

void NodeEraser::rebind(Mesh &mesh) {
    assert(mesh.n_vertices() == impl_->mesh->n_vertices() &&
           mesh.n_faces() == impl_->face_head.size());
    impl_->mesh = &mesh;
    advise_huge(*impl_);
    if (impl_->fans_stale)
        rebuild_fans(*impl_); // here, not in the first update (23 ms of a 30 fps descent's frame)
    if (impl_->grid_w > 0 && impl_->tile_z.empty())
        build_tile_z(*impl_); // and these (a pass over every sample)
}

const Mesh &NodeEraser::mesh() const { return *impl_->mesh; }
std::int64_t NodeEraser::live_nodes() const { return impl_->live; }
std::int64_t NodeEraser::live_triangles() const { return impl_->live_faces; }

// The erased node to recover first on the way to erased node v: v, or the end of the chain of the
// erases v's recovery depends on, taking at each step the erased ring node nearest v (in xy for a
// TIN). The chain then stays over v, and each node recovered refines the faces around it: on the
// three N42E001 paths at 30 frames per second, 8-11 % fewer recoveries (and 16-19 % fewer nodes
// erased again by the same update) than the first erased ring node, for 4-6 % less time per frame.
// The chain is kept in s.chain: the update asks again for the same v once the chain's end is
// back, and the nodes before the first one recovered since chose as they would now (a recovery
// only takes nodes out of their choice), so the walk resumes there instead of from v (the walks
// from v were 6 % of a 4097² fly-over's time, each node's ring read again per step).
static std::uint32_t ready_dependency(NodeEraser::Impl &s, std::uint32_t v) {
    std::vector<std::uint32_t> &chain = s.chain;
    if (chain.empty() || chain.front() != v) {
        chain.assign(1, v);
    } else {
        std::size_t kept = 1;
        while (kept < chain.size() && s.record_of[chain[kept]] >= 0)
            ++kept;
        chain.resize(kept);
    }
    const glm::dvec3 target = to_glm(node_point(s, v));
    for (;;) {
        const std::uint32_t at = chain.back();
        std::array<std::uint32_t, 4> scratch;
        const ErasedRing erased = erased_ring(s, at, scratch);
        const std::uint32_t *ring = erased.nodes;
        std::uint32_t next = at;
        double nearest = INFINITY;
        for (int i = 0; i < erased.size; ++i)
            if (s.record_of[ring[i]] >= 0) {
                glm::dvec3 d = to_glm(node_point(s, ring[i])) - target;
                if (s.xy)
                    d.z = 0.0;
                if (glm::dot(d, d) < nearest) {
                    nearest = glm::dot(d, d);
                    next = ring[i];
                }
            }
        if (next == at)
            return at;
        chain.push_back(next);
    }
}

// Lists at least this long get blocks when worst_swallowed scans them whole.
constexpr std::size_t k_block_list = 256;
constexpr int k_block_side = 8; // blocks: a k_block_side² grid over the face's box in xy
constexpr std::size_t k_kept_scratch = 4096; // larger scratch is released after use

// Puts the nodes of face f's list (`deviation(u)` gives node u's) in runs by the square of a grid
// over the face's box in xy that holds them, and keeps each run as a block: its first node, its
// length, its nodes' largest deviation and their box. A scan then skips a block whose deviation
// times the largest weight in its box cannot matter (a face of ~10^5 nodes on a flat, in sight of
// a low eye, was weighed node by node every frame: ~570 k weights per frame on the flight
// benchmark's 2049² valley path).
template <class Deviation>
static void build_blocks(NodeEraser::Impl &s, FH f, const glm::dvec2 &lo, const glm::dvec2 &hi,
                         const Deviation &deviation) {
    std::vector<std::int32_t> &nodes = s.block_scratch;
    nodes.clear();
    for (std::int32_t u = s.face_head[f.idx()]; u >= 0; u = s.next_swallowed[u])
        nodes.push_back(u);
    constexpr int cells = k_block_side * k_block_side;
    std::array<std::uint32_t, cells + 1> start{};
    std::vector<std::uint8_t> &cell_of_node = s.block_cell_scratch;
    cell_of_node.resize(nodes.size());
    const glm::dvec2 scale = double(k_block_side) / glm::max(hi - lo, glm::dvec2(1e-300));
    for (std::size_t k = 0; k < nodes.size(); ++k) {
        const glm::dvec3 p = to_glm(node_point(s, std::uint32_t(nodes[k])));
        const int cx = std::clamp(int((p.x - lo.x) * scale.x), 0, k_block_side - 1);
        const int cy = std::clamp(int((p.y - lo.y) * scale.y), 0, k_block_side - 1);
        cell_of_node[k] = std::uint8_t(cy * k_block_side + cx);
        ++start[cell_of_node[k] + 1];
    }
    for (int c = 0; c < cells; ++c)
        start[c + 1] += start[c];
    std::vector<std::int32_t> &order = s.block_order_scratch;
    order.resize(nodes.size());
    std::array<std::uint32_t, cells> fill;
    std::copy(start.begin(), start.end() - 1, fill.begin());
    std::vector<Block> blocks;
    for (std::size_t k = 0; k < nodes.size(); ++k)
        order[fill[cell_of_node[k]]++] = std::int32_t(k);
    for (int c = 0; c < cells; ++c) {
        if (start[c] == start[c + 1])
            continue;
        Block b;
        b.head = nodes[std::size_t(order[start[c]])];
        b.count = start[c + 1] - start[c];
        glm::dvec3 blo(INFINITY), bhi(-INFINITY);
        double dev = 0.0;
        for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) {
            const std::int32_t u = nodes[std::size_t(order[k])];
            const glm::dvec3 p = to_glm(node_point(s, std::uint32_t(u)));
            blo = glm::min(blo, p);
            bhi = glm::max(bhi, p);
            dev = std::max(dev, double(float_up(deviation(u))));
        }
        b.dev = dev;
        b.lo = blo;
        b.hi = bhi;
        blocks.push_back(b);
    }
    // Relink the list run by run.
    s.face_head[f.idx()] = nodes[std::size_t(order.front())];
    for (std::size_t k = 0; k + 1 < order.size(); ++k)
        s.next_swallowed[nodes[std::size_t(order[k])]] = nodes[std::size_t(order[k + 1])];
    s.next_swallowed[nodes[std::size_t(order.back())]] = -1;
    s.face_blocks[f.idx()] = std::move(blocks);
    s.face_blocked[f.idx()] = 1;
    if (nodes.capacity() > k_kept_scratch) {
        // A face over a whole flat (10^5 nodes and more) is blocked once: its scratch goes.
        std::vector<std::int32_t>().swap(nodes);
        std::vector<std::uint8_t>().swap(s.block_cell_scratch);
        std::vector<std::int32_t>().swap(s.block_order_scratch);
    }
}

// The box face f's swallowed nodes lie in (f's corners a, b, c): within its largest deviation of it
// (with a margin for the float rounding of that deviation), a TIN's inside it in xy and vertically
// off it, a surface mesh's at that distance of it in any direction, so the box widens on every
// axis.
static std::pair<glm::dvec3, glm::dvec3> swallowed_box(const NodeEraser::Impl &s, FH f,
                                                       const glm::dvec3 &a, const glm::dvec3 &b,
                                                       const glm::dvec3 &c) {
    const double dz = 1.001 * double(s.face_maxdev[f.idx()]);
    const glm::dvec3 margin = s.xy ? glm::dvec3(0.0, 0.0, dz) : glm::dvec3(dz);
    return {glm::min(glm::min(a, b), c) - margin, glm::max(glm::max(a, b), c) + margin};
}

// The eye's move and the axis's turn since the view of update `at`, or null when a bound made under
// that view does not carry over to the current one.
static const NodeEraser::Impl::Since *since(const NodeEraser::Impl &s, std::uint32_t at) {
    if (!keeps_bounds(s) || at == 0 || s.updates - at >= NodeEraser::Impl::k_seen_views)
        return nullptr;
    const NodeEraser::Impl::Since &d = s.since[at % NodeEraser::Impl::k_seen_views];
    return d.ok ? &d : nullptr;
}

// The factor by which the weight of a node at least `nearest` from the current eye may have grown
// since `d` (see Impl::face_seen_dev); infinite when the eye moved that far. `cone`: the node was
// inside the view cone then (peripheral factor 1, which no view exceeds): the distance's share
// alone.
static double weight_growth(const NodeEraser::Impl &s, const NodeEraser::Impl::Since &d,
                            double nearest, bool cone) {
    if (!(d.moved < nearest))
        return INFINITY;
    const double x = d.moved / nearest;
    return cone ? 1.0 + x : (1.0 + x) * std::exp((d.turn + std::asin(x)) / s.weigher.falloff());
}

// The logarithms of that factor and of the one by which such a weight may have shrunk
// ((1 - x) * exp(-(turn + asin x) / falloff) with x = moved / nearest, since the distance then was
// at least nearest - moved; `cone`: the node is inside the view cone now, so only the distance's
// share), over-estimated without transcendental functions: ln(1 + x) <= x, -ln(1 - x) <=
// x / (1 - x) and asin x <= x / sqrt(1 - x²). For the per-node tests an update makes for every
// live node it visits.
static double log_growth(const NodeEraser::Impl &s, const NodeEraser::Impl::Since &d,
                         double nearest, bool cone) {
    if (!(d.moved < nearest))
        return INFINITY;
    const double x = d.moved / nearest;
    return cone ? x : x + (d.turn + x / std::sqrt(1.0 - x * x)) / s.weigher.falloff();
}

static double log_shrink(const NodeEraser::Impl &s, const NodeEraser::Impl::Since &d,
                         double nearest, bool cone) {
    if (!(d.moved < nearest))
        return INFINITY;
    const double x = d.moved / nearest;
    const double angle = cone ? 0.0 : (d.turn + x / std::sqrt(1.0 - x * x)) / s.weigher.falloff();
    return x / (1.0 - x) + angle;
}

// The same bounds linear in x for x <= 1/4, where x / (1 - x) <= 4/3 x and asin x <= x / sqrt(1 -
// x²) <= 1.0328 x: growth <= x (in the cone) or (1 + 1.0328 / falloff) x + a / falloff, shrink <=
// 4/3 x (in the cone) or (4/3 + 1.0328 / falloff) x + a / falloff. Whether a bound of logarithmic
// margin `slack` (after the turn's share a / falloff) holds for nodes within r of p, the eye having
// moved by `moved`, with `per_x` the factor of x: slack > per_x x, with x <= 1/4, tested without a
// division or a square root (the exact tests' cost the update's walk over the live nodes paid for
// every node: 27 % of a low, slow observer's frames on N42E001).
constexpr double k_asin_quarter = 1.0329; // > 1 / sqrt(1 - 1/16)
static bool moved_within(const glm::dvec3 &eye, const glm::dvec3 &p, double r, double moved,
                         double slack, double per_x) {
    if (!(slack > 0.0))
        return false;
    const glm::dvec3 d = p - eye;
    const double d2 = glm::dot(d, d);
    const double quarter = r + 4.0 * moved; // x <= 1/4: |p - eye| - r >= 4 moved
    if (!(d2 >= quarter * quarter))
        return false;
    // slack (|p - eye| - r) > per_x moved, squared: both sides are positive.
    const double rhs = slack * r + per_x * moved * (1.0 + 1e-9);
    return slack * slack * d2 > rhs * rhs * (1.0 + 1e-9);
}

// Live node l's seen bound (LiveNode::seen_log) carried to the current view, as a logarithm
// (+inf: none that carries over).
static double seen_now(const NodeEraser::Impl &s, const LiveNode &l) {
    if (!(l.seen_log < INFINITY))
        return INFINITY;
    if (l.seen_at == s.updates)
        return double(l.seen_log);
    const NodeEraser::Impl::Since *d = since(s, l.seen_at);
    if (!d)
        return INFINITY;
    const double nearest = glm::length(to_glm(l.p) - s.view.eye) - double(l.reach);
    return double(l.seen_log) + log_growth(s, *d, nearest, l.seen_cone);
}

// Before an update's erase of h.v: its ring nodes' seen bounds carried to this view (+inf: none),
// for carry_seen.
static void seen_before(NodeEraser::Impl &s, const Hole &h, std::array<double, k_max_ring> &old) {
    const bool kept = !s.fans_stale && keeps_bounds(s);
    for (int i = 0; i < h.n; ++i)
        old[std::size_t(i)] = kept ? seen_now(s, live_node(s, node_of(s, h.r[i]))) : INFINITY;
}

// After it: each ring node gets back a seen bound, which widen_fans dropped, made under this view:
// its faces the erase left as they were are within their old bound (`old`), and the new ones
// within the erase's cost, the exact largest weighted deviation of the samples in the hole. Else
// the next update walked their fans again: on the 4097² valley drive at 30 frames per second,
// 1,020 nodes per frame had their fans walked for want of a seen bound, 580 with it, and the frames
// took 1-5 % less (scratch runs, the same nodes erased and recovered).
static void carry_seen(NodeEraser::Impl &s, const Hole &h,
                       const std::array<double, k_max_ring> &old) {
    const double cost = h.cost > 0.0 ? std::log(h.cost * (1.0 + 1e-6)) : -INFINITY;
    for (int i = 0; i < h.n; ++i) {
        if (!(old[std::size_t(i)] < INFINITY))
            continue;
        LiveNode &l = live_node(s, node_of(s, h.r[i]));
        const glm::dvec3 p = to_glm(l.p), r(double(l.reach));
        l.seen_log = float_up(std::max(old[std::size_t(i)], cost) + 1e-6);
        l.seen_at = s.updates;
        l.seen_cone = s.weigher.in_cone(p - r, p + r);
    }
}

// The bound face f's seen bound gives under the current view for nodes in the box [lo, hi] (its
// swallowed nodes' box), or infinity when it has none that carries over.
static double seen_bound(const NodeEraser::Impl &s, FH f, const glm::dvec3 &lo,
                         const glm::dvec3 &hi) {
    if (s.face_seen_dev[f.idx()] < 0.0f)
        return INFINITY;
    const NodeEraser::Impl::Since *d = since(s, s.face_seen[f.idx()] >> 1);
    if (!d)
        return INFINITY;
    const double nearest = glm::length(glm::clamp(s.view.eye, lo, hi) - s.view.eye);
    return double(s.face_seen_dev[f.idx()]) *
           weight_growth(s, *d, nearest, s.face_seen[f.idx()] & 1) * k_rounded_weight *
           (1.0 + 1e-9);
}

// Face f's swallowed nodes, in the box [lo, hi], have weighted deviations <= seen under the
// current view: kept for the updates that follow (see Impl::face_seen_dev).
static void remember_seen(NodeEraser::Impl &s, FH f, double seen, const glm::dvec3 &lo,
                          const glm::dvec3 &hi) {
    s.face_seen_dev[f.idx()] = float_up(seen * (1.0 + 1e-9));
    s.face_seen[f.idx()] = s.updates << 1 | std::uint32_t(s.weigher.in_cone(lo, hi));
}

// The worst swallowed node of face f whose weighted deviation exceeds `above`, and that weighted
// deviation (-1 when none does).
static std::pair<std::int32_t, double> worst_swallowed(NodeEraser::Impl &s, FH f, double above) {
    const Mesh &m = *s.mesh;
    std::int32_t u = s.face_head[f.idx()];
    if (u < 0)
        return {-1, above};
    HH he = m.halfedge_handle(f);
    const glm::dvec3 a = to_glm(m.point(m.from_vertex_handle(he)));
    const glm::dvec3 b = to_glm(m.point(m.to_vertex_handle(he)));
    const glm::dvec3 c = to_glm(m.point(m.to_vertex_handle(m.next_halfedge_handle(he))));
    const glm::dvec3 normal = glm::cross(b - a, c - a);
    const double slope =
        s.xy ? glm::length(glm::dvec2(normal.x, normal.y)) / std::abs(normal.z) : 0.0;
    // A node's weight is looked up only when its deviation times a bound of the weights over the
    // face (TINs: over its corners' box in xy, within its largest deviation in z) could beat the
    // worst so far; that bound may clear the whole face at once (with a margin for the float
    // rounding of the stored deviation and of its recomputation here).
    std::pair<std::int32_t, double> worst{-1, above};
    double weight_bound = INFINITY;
    if (s.xy && !s.unit_weights) {
        weight_bound = swallowed_weight_bound(s, a, b, c, s.face_maxdev[f.idx()]);
        if (!(1.001 * double(s.face_maxdev[f.idx()]) * weight_bound > above))
            return worst;
    }
    const bool screen = keeps_bounds(s);
    const auto [box_lo, box_hi] = swallowed_box(s, f, a, b, c);
    if (screen && !(seen_bound(s, f, box_lo, box_hi) > above))
        return worst;
    // A TIN face's height at (x, y), and the deviation from f of a swallowed node at p, computed
    // the same way by every scan.
    auto plane_at = [&](double x, double y) {
        const double b0 = orient({b.x, b.y}, {c.x, c.y}, {x, y}) / normal.z;
        const double b1 = orient({c.x, c.y}, {a.x, a.y}, {x, y}) / normal.z;
        return b0 * a.z + b1 * b.z + (1.0 - b0 - b1) * c.z;
    };
    auto deviation_at = [&](const glm::dvec3 &p) {
        if (!s.xy)
            return triangle_distance(p, a, b, c);
        // The same float-rounding widening as locate(): the bound is never overstated.
        return std::abs(p.z - plane_at(p.x, p.y)) +
               rounding_margin(std::max(std::abs(p.x), std::abs(p.y)), slope);
    };
    auto deviation = [&](std::int32_t u) {
        return deviation_at(to_glm(node_point(s, std::uint32_t(u))));
    };
    auto visit = [&](std::int32_t u, double dev, double bound) {
        if (!(dev * bound > worst.second))
            return;
        const double w = weighted(s, std::uint32_t(u), dev);
        if (w > worst.second)
            worst = {u, w};
    };
    if (s.grid_w > 0) {
        // Band by band, skipping a band whose largest weight cannot make the face's largest
        // deviation matter; or, on a large face, tile by tile with each tile's.
        const double dz = 1.001 * double(s.face_maxdev[f.idx()]);
        const double zlo = std::min({a.z, b.z, c.z}) - dz, zhi = std::max({a.z, b.z, c.z}) + dz;
        const std::uint32_t ia = node_of(s, m.from_vertex_handle(he)),
                            ib = node_of(s, m.to_vertex_handle(he)),
                            ic = node_of(s, m.to_vertex_handle(m.next_halfedge_handle(he)));
        std::vector<float> *tiles = lattice_tiles(s, f, ia, ib, ic, plane_at, slope);
        // Visits sample(u, q, dev, bound) for each sample (point q, deviation dev) of a tile or
        // band whose largest deviation times its largest weight (`bound`) may exceed `above`.
        const auto scan = [&](const double &above, const auto &sample) {
            const auto bound_over = [&](const glm::dvec2 &lo, const glm::dvec2 &hi) {
                return s.weigher.bound({lo, zlo}, {hi, zhi}) * k_rounded_weight;
            };
            if (tiles) {
                scan_tiles(
                    s, ia, ib, ic, *tiles,
                    [&](const glm::dvec2 &lo, const glm::dvec2 &hi, double dev) {
                        const double bound = bound_over(lo, hi);
                        return 1.001 * dev * bound > above ? bound : -1.0;
                    },
                    deviation_at, sample);
                return;
            }
            scan_lattice(
                s, ia, ib, ic,
                [&](const glm::dvec2 &lo, const glm::dvec2 &hi) {
                    if (s.unit_weights)
                        return 1.0;
                    const double bound = bound_over(lo, hi);
                    return dz * bound > above ? bound : -1.0;
                },
                [&](std::uint32_t v, const Mesh::Point &p, double bound) {
                    const glm::dvec3 q = to_glm(p);
                    sample(v, q, deviation_at(q), bound);
                    return true;
                });
        };
        scan(worst.second, [&](std::uint32_t v, const glm::dvec3 &, double dev, double bound) {
            visit(std::int32_t(v), dev, bound);
        });
        if (screen && worst.first < 0) {
            // The largest weighted deviation, for the updates that follow: a band, tile or sample
            // that its bound shows cannot raise it is not weighed (weighing every sample took a
            // third of a low observer's frames on 4097²; the maximum is the same).
            double seen = 0.0;
            scan(seen, [&](std::uint32_t, const glm::dvec3 &q, double dev, double bound) {
                if (dev * bound > seen)
                    seen = std::max(seen, dev * s.weigher(q));
            });
            remember_seen(s, f, seen, box_lo, box_hi);
        }
        return worst;
    }
    if (s.face_blocked[f.idx()]) {
        for (const Block &block : s.face_blocks.find(f.idx())->second) {
            const double bound = s.weigher.bound(block.lo, block.hi) * k_rounded_weight;
            if (!(block.dev * bound > worst.second))
                continue;
            u = block.head;
            for (std::uint32_t k = 0; k < block.count; ++k, u = s.next_swallowed[u])
                visit(u, deviation(u), bound);
        }
        return worst;
    }
    std::size_t length = 0;
    double seen = 0.0;
    for (; u >= 0; u = s.next_swallowed[u], ++length) {
        const glm::dvec3 q = to_glm(node_point(s, std::uint32_t(u)));
        const double dev = deviation_at(q);
        visit(u, dev, weight_bound);
        if (screen)
            seen = std::max(seen, dev * s.weigher(q));
    }
    if (screen && worst.first < 0)
        remember_seen(s, f, seen, box_lo, box_hi);
    // A long list scanned whole gets blocks (when a weight bound can use them).
    if (std::isfinite(weight_bound) && length >= k_block_list)
        build_blocks(s, f, glm::dvec2(glm::min(glm::min(a, b), c)),
                     glm::dvec2(glm::max(glm::max(a, b), c)), deviation);
    return worst;
}

// A bound on the weighted deviation of the swallowed nodes of live node l's fan under the current
// view, from its bounds alone: the largest deviation times the largest weight in the cube they lie
// in.
static double fan_bound(const NodeEraser::Impl &s, const LiveNode &l) {
    if (l.fan_dev <= 0.0f)
        return 0.0;
    const glm::dvec3 p = to_glm(l.p);
    const glm::dvec3 r(double(l.reach));
    return double(l.fan_dev) * s.weigher.bound(p - r, p + r) * k_rounded_weight;
}

// A bound on the weighted deviation of live face f's swallowed nodes under the current view: the
// smaller of its seen bound carried over and their largest deviation times the largest weight in
// the box they lie in, without visiting them (0 when it swallowed none).
static double face_bound(const NodeEraser::Impl &s, FH f) {
    const Mesh &m = *s.mesh;
    if (s.face_head[f.idx()] < 0 || s.face_maxdev[f.idx()] <= 0.0f)
        return 0.0;
    const HH he = m.halfedge_handle(f);
    const auto [lo, hi] = swallowed_box(
        s, f, to_glm(m.point(m.from_vertex_handle(he))), to_glm(m.point(m.to_vertex_handle(he))),
        to_glm(m.point(m.to_vertex_handle(m.next_halfedge_handle(he)))));
    return std::min(double(s.face_maxdev[f.idx()]) * s.weigher.bound(lo, hi) * k_rounded_weight,
                    seen_bound(s, f, lo, hi));
}

// The nodes swallowed by the faces live node l seeds have weighted deviations <= bound under the
// current view.
static void remember_fan(const NodeEraser::Impl &s, LiveNode &l, double bound) {
    if (keeps_bounds(s)) {
        const glm::dvec3 p = to_glm(l.p), r(double(l.reach));
        l.seen_log = float_up(std::log(bound) + 1e-6);
        l.seen_at = s.updates;
        l.seen_cone = s.weigher.in_cone(p - r, p + r);
    }
}

// Whether the nodes swallowed by the faces live node l seeds cost at most `recover_above` by the
// node's own bounds: its seen bound carried over, then its fan's box (remembered when it clears
// them).
static bool fan_cleared(const NodeEraser::Impl &s, LiveNode &l, double recover_above,
                        double log_recover) {
    if (l.seen_log < INFINITY) {
        if (const NodeEraser::Impl::Since *d = since(s, l.seen_at)) {
            const double falloff = s.weigher.falloff();
            if (moved_within(s.view.eye, to_glm(l.p), double(l.reach), d->moved,
                             log_recover - double(l.seen_log) -
                                 (l.seen_cone ? 0.0 : d->turn / falloff),
                             l.seen_cone ? 1.0 : 1.0 + k_asin_quarter / falloff))
                return true;
            if (seen_now(s, l) <= log_recover)
                return true;
        }
    }
    const double box = fan_bound(s, l);
    if (!(box > recover_above)) {
        remember_fan(s, l, box);
        return true;
    }
    return false;
}

// Sets live node l's fan bounds from its fan as it stands: the largest deviation of its faces'
// swallowed nodes, and their reach (the farthest corner, plus that deviation).
static void fan_extent(const NodeEraser::Impl &s, LiveNode &l) {
    const Mesh &m = *s.mesh;
    const glm::dvec3 px = to_glm(l.p);
    double far2 = 0.0;
    float fan_dev = 0.0f;
    for (auto he : m.voh_range(VH(l.vertex))) {
        const glm::dvec3 d = to_glm(m.point(m.to_vertex_handle(he))) - px;
        far2 = std::max(far2, glm::dot(d, d));
        const FH f = m.face_handle(he);
        if (f.is_valid())
            fan_dev = std::max(fan_dev, s.face_maxdev[f.idx()]);
    }
    l.reach = float_up(std::sqrt(far2) + double(fan_dev));
    l.fan_dev = fan_dev;
    l.fan_exact = true;
}

// The fan bounds of every live node and cell, from the fans as they stand (see Impl::fans_stale).
static void rebuild_fans(NodeEraser::Impl &s) {
    for (Cell &cell : s.cells) {
        cell.fan_dev = 0.0f;
        cell.reach = 0.0f;
    }
    for (LiveNode &l : s.live_list) {
        fan_extent(s, l);
        l.seen_log = INFINITY;
        Cell &cell = s.cells[l.cell];
        cell.fan_dev = std::max(cell.fan_dev, l.fan_dev);
        cell.reach = std::max(cell.reach, l.reach);
    }
    s.fans_stale = false;
}

// Seeds the recover worklist with the faces of live node l's fan whose swallowed nodes may cost
// more than `recover_above` (l's own bounds did not clear them): tightens l's bounds from its fan
// as it stands unless they are that already (LiveNode::fan_exact), which may clear them, else tries
// each face's. Each face is seeded by the node its halfedge leaves from, so once, and l's seen
// bound need only cover the faces it seeds: a face near the bound makes one node walk its fan each
// update, not three.
static void seed_fan(NodeEraser::Impl &s, LiveNode &l, double recover_above,
                     std::vector<FH> &work) {
    const Mesh &m = *s.mesh;
    const VH x(l.vertex);
    if (!l.fan_exact)
        fan_extent(s, l); // else its bounds are what the walk would give
    const double box = fan_bound(s, l);
    if (!(box > recover_above)) {
        remember_fan(s, l, box);
        return;
    }
    double most = 0.0;
    for (auto he : m.voh_range(x)) {
        const FH f = m.face_handle(he);
        if (!f.is_valid() || m.halfedge_handle(f) != he)
            continue; // another corner's to seed
        const double bound = face_bound(s, f);
        most = std::max(most, bound);
        if (bound > recover_above)
            work.push_back(f);
    }
    remember_fan(s, l, most);
}

UpdateStats NodeEraser::update(const View &view, double recover_above, double erase_below) {
    Impl &s = *impl_;
    assert(s.options.significance.model != SpModel::vertical && erase_below <= recover_above);
    Mesh &m = *s.mesh;
    if (s.absent_for_good)
        throw std::logic_error("NodeEraser::update: the samples the input TIN left out need "
                               "EraseOptions::absent_history to follow a view");
    UpdateStats stats;
    const std::int64_t entered = s.entered, fans_kept = s.fans_kept;
    if (s.live > k_regrid_ratio * s.grid_live || k_regrid_ratio * s.live < s.grid_live)
        regrid(s);
    if (s.fans_stale)
        rebuild_fans(s);

    // New weights; the old ones tell how far each node's significance fell.
    Stopwatch clock;
    s.view = view;
    s.has_view = true;
    if (s.options.significance.model == SpModel::paper)
        s.focal_distance = std::max(focal_point(m, view).distance, 1e-9);
    s.weigher = Weigher(&s.view, s.options.significance);
    new_weights(s, false);
    s.seen_views[++s.updates % Impl::k_seen_views] = view;
    for (std::uint32_t i = 0; i < Impl::k_seen_views; ++i) {
        const View &then = s.seen_views[i];
        Impl::Since &d = s.since[i];
        d.ok = then.fov_deg == view.fov_deg && then.viewport_w == view.viewport_w &&
               then.viewport_h == view.viewport_h;
        d.moved = glm::length(view.eye - then.eye);
        d.turn = std::acos(std::clamp(glm::dot(then.axis(), view.axis()), -1.0, 1.0));
    }
    stats.ms_weights = clock.ms();

    // recover: a worklist of faces, seeded with every face whose swallowed nodes may exceed the
    // bound (their largest deviation over the distance to the box they lie in says so, without
    // visiting them); a face that gets its worst node back is replaced by the fans of the nodes
    // re-inserted.
    // The grid skips the cells whose bounds clear every node in them; the walk over the live
    // nodes rebuilds those bounds (widen_fans raises them as the update changes fans).
    clock.reset();
    std::vector<std::uint8_t> &visit = s.cell_visit;
    visit.resize(s.cells.size());
    for (std::uint32_t c = 0; c < std::uint32_t(s.cells.size()); ++c) {
        Cell &cell = s.cells[c];
        const auto [lo, hi] = cell_box(s, c, double(cell.reach));
        visit[c] =
            cell.fan_dev > 0.0f &&
            double(cell.fan_dev) * s.weigher.bound(lo, hi) * k_rounded_weight > recover_above;
        cell.fan_dev = 0.0f;
        cell.reach = 0.0f;
    }
    std::vector<FH> work;
    std::vector<std::uint32_t> recovered;
    s.chain.clear(); // the erases since the last update may have changed any choice
    const double log_recover = std::log(recover_above);
    for (LiveNode &l : s.live_list) {
        if (visit[l.cell] && !fan_cleared(s, l, recover_above, log_recover))
            seed_fan(s, l, recover_above, work);
        Cell &cell = s.cells[l.cell];
        cell.fan_dev = std::max(cell.fan_dev, l.fan_dev);
        cell.reach = std::max(cell.reach, l.reach);
    }
    while (!work.empty()) {
        const FH f = work.back();
        work.pop_back();
        if (m.status(f).deleted())
            continue;
        ++stats.faces_checked;
        const std::int32_t u = worst_swallowed(s, f, recover_above).first;
        if (u < 0)
            continue;
        // Top down: the erase u's recovery waits for that can be undone now comes back alone, and f
        // is checked again. The new fan often brings u within the bound before its whole closure
        // is back (bottom up, most of a closure was erased again by the same update).
        const std::uint32_t x = ready_dependency(s, std::uint32_t(u));
        reinsert(s, x);
        ++stats.recovered;
        s.flags[x] |= k_recovered;
        recovered.push_back(x);
        // Re-evaluated by this update's erase: a node recovered only because a worse one depended
        // on it may cost little, and a key of "significant" would keep it forever. So are its ring
        // nodes: their fans gave x its faces back, so their erase costs changed and the bounds on
        // them (LiveNode::star_dev, low_log) no longer hold. Left as they were, the 1201² valley
        // drive at 30 frames per second kept 4 % more nodes than its erase bound asks for.
        mark_dirty(s, x);
        for (auto r : m.vv_range(vh(s, x)))
            if (!(s.flags[node_of(s, r)] & k_locked))
                mark_dirty(s, node_of(s, r));
        for (auto g : m.vf_range(vh(s, x)))
            work.push_back(g);
        if (!m.status(f).deleted())
            work.push_back(f);
    }
    stats.entered = s.entered - entered;
    stats.fans_kept = s.fans_kept - fans_kept;
    stats.ms_recover = clock.ms();

    // erase: only nodes whose cost may have fallen to the bound are re-evaluated.
    // The grid skips the cells where no node is dirty and every node's cost is over the bound: the
    // least star deviation times the least weight in the box the stars lie in says so.
    clock.reset();
    for (std::uint32_t c = 0; c < std::uint32_t(s.cells.size()); ++c) {
        Cell &cell = s.cells[c];
        const auto [lo, hi] = cell_box(s, c, double(cell.reach));
        visit[c] = cell.dirty || !(double(cell.star_dev) * s.weigher.lower(lo, hi) > erase_below);
        cell.star_dev = INFINITY;
    }
    std::vector<std::uint32_t> candidates;
    std::vector<LiveNode *> unsettled;
    const double log_below = std::log(erase_below);
    for (LiveNode &l : s.live_list) {
        Cell &cell = s.cells[l.cell];
        cell.star_dev = std::min(cell.star_dev, l.star_dev);
        if (!visit[l.cell])
            continue;
        // A node that is not dirty (mark_dirty drops low_log) and whose cost cannot have fallen
        // to the bound since it was last known: the star lies within reach of the node.
        if (l.low_log == INFINITY)
            continue; // parked
        if (l.low_log > -INFINITY) {
            if (const Impl::Since *d = since(s, l.low_at)) {
                // The shrink outside the view cone bounds the one inside it: the cone test (a
                // square root and a division per node, 15 % of a still observer's update) only
                // when that bound does not settle the node.
                const glm::dvec3 p = to_glm(l.p), r(double(l.reach));
                const double falloff = s.weigher.falloff();
                if (moved_within(s.view.eye, p, r.x, d->moved,
                                 double(l.low_log) - log_below - d->turn / falloff,
                                 4.0 / 3.0 + k_asin_quarter / falloff))
                    continue;
                const double nearest = glm::length(p - s.view.eye) - r.x;
                if (double(l.low_log) - log_shrink(s, *d, nearest, false) > log_below ||
                    (s.weigher.in_cone(p - r, p + r) &&
                     double(l.low_log) - log_shrink(s, *d, nearest, true) > log_below))
                    continue;
            }
        }
        unsettled.push_back(&l);
    }
    // The nodes the bounds above did not settle, apart: their flags and their star's height are
    // each a cache miss, asked for a few nodes ahead (the erase 2-5 % faster on the 4097² first
    // flights at 30 frames per second, scratch runs).
    constexpr std::size_t k_ahead = 8;
    for (std::size_t i = 0; i < unsettled.size(); ++i) {
        if (i + k_ahead < unsettled.size()) {
            const LiveNode &ahead = *unsettled[i + k_ahead];
            __builtin_prefetch(&s.flags[ahead.node]);
            if (s.lattice)
                __builtin_prefetch(&s.lattice->z[ahead.star]);
        }
        LiveNode &l = *unsettled[i];
        const std::uint32_t x = l.node;
        if (s.flags[x] & k_locked)
            continue;
        const float key = node_key(s, l);
        if (!std::isfinite(key))
            continue; // its hole cannot be re-triangulated: only a change of its ring can help
        if (!(s.flags[x] & k_dirty)) {
            // The cost under this view is at least the star's deviation times its weight now.
            const double least = double(l.star_dev) * weight_of(s, l.star);
            if (least > erase_below) {
                store_node_key(s, l, float_down(least));
                remember_low(s, l, least);
                continue;
            }
        }
        ++stats.candidates;
        s.flags[x] |= k_dirty;
        candidates.push_back(x);
    }
    s.reerased = 0;
    const std::int64_t evaluations = s.evaluations;
    stats.erased = sweep_dirty(s, erase_below, std::move(candidates), k_update_cap);
    stats.evaluations = s.evaluations - evaluations;
    stats.reerased = s.reerased;
    for (const std::uint32_t x : recovered)
        s.flags[x] &= std::uint8_t(~k_recovered);
    for (Cell &cell : s.cells)
        cell.dirty = false; // the sweep left no live node dirty
    if (s.advised[0] &&
        (s.advised[0] != m.points() || (m.n_edges() > 0 && s.advised[1] != &m.edge(EH(0))) ||
         (m.n_faces() > 0 && s.advised[2] != &m.face(FH(0)))))
        advise_huge(s); // an array grew out of its room
    stats.ms_erase = clock.ms();
    return stats;
}

NodeEraser::Cost NodeEraser::erase_cost(Mesh::VertexHandle v) {
    Impl &s = *impl_;
    const std::uint32_t x = node_of(s, v);
    if (s.record_of[x] >= 0)
        throw std::invalid_argument("NodeEraser::erase_cost: the node is erased");
    Cost out;
    if (s.xy && s.area_per_node > 0.0)
        out.covered = covered_estimate(s, x);
    if (s.flags[x] & k_locked)
        return out;
    const std::int64_t evaluations = s.evaluations;
    if (evaluate(s, v, INFINITY)) {
        out.cost = s.hole.cost;
        if (s.grid_w > 0)
            out.covered = std::max(out.covered, double(lattice_inside(s, s.hole)));
    }
    s.evaluations = evaluations;
    return out;
}

EraseStats NodeEraser::measure() const {
    const Impl &s = *impl_;
    const Mesh &m = *s.mesh;
    EraseStats stats;
    stats.output_nodes = s.live;
    stats.output_triangles = s.live_faces;
    const double k = s.has_view ? s.view.k() : 0.0;
    // Each TIN face's bounds on what its swallowed nodes can show: its largest deviation, alone,
    // times the largest weight in its box and times k over the box's distance (a surface mesh's
    // faces get no bounds: each is scanned). Faces go from the largest weighted bound down, and a
    // face whose three bounds cannot raise the maxima found so far is not scanned (the erase
    // leaves most faces near the bound, so the first few settle the maxima).
    struct Bounded {
        double weighted, screen, vertical;
        FH f;
    };
    std::vector<Bounded> faces;
    faces.reserve(std::size_t(s.live_faces));
    for (auto f : m.faces()) {
        if (s.face_head[f.idx()] < 0 || m.status(f).deleted())
            continue;
        const HH he = m.halfedge_handle(f);
        const glm::dvec3 a = to_glm(m.point(m.from_vertex_handle(he))),
                         b = to_glm(m.point(m.to_vertex_handle(he))),
                         c = to_glm(m.point(m.to_vertex_handle(m.next_halfedge_handle(he))));
        const double dev = 1.001 * double(s.face_maxdev[f.idx()]);
        const auto [lo, hi] = swallowed_box(s, f, a, b, c);
        const double near = glm::length(glm::clamp(s.view.eye, lo, hi) - s.view.eye);
        faces.push_back({s.xy ? dev * s.weigher.bound(lo, hi) * k_rounded_weight : INFINITY,
                         s.xy && s.has_view ? dev * k / near : INFINITY, s.xy ? dev : INFINITY, f});
    }
    std::sort(faces.begin(), faces.end(),
              [](const Bounded &x, const Bounded &y) { return x.weighted > y.weighted; });
    for (const Bounded &bounded : faces) {
        if (!(bounded.weighted > stats.max_weighted) && !(bounded.vertical > stats.max_vertical) &&
            (!s.has_view || !(bounded.screen > stats.max_screen_px)))
            continue;
        const FH f = bounded.f;
        std::int32_t u = s.face_head[f.idx()];
        HH he = m.halfedge_handle(f);
        const VH va = m.from_vertex_handle(he), vb = m.to_vertex_handle(he),
                 vc = m.to_vertex_handle(m.next_halfedge_handle(he));
        const glm::dvec3 a = to_glm(m.point(va)), b = to_glm(m.point(vb)), c = to_glm(m.point(vc));
        const glm::dvec3 normal = glm::cross(b - a, c - a);
        const double area = normal.z;
        auto add = [&](std::int32_t node) {
            const glm::dvec3 p = to_glm(node_point(s, std::uint32_t(node)));
            double dev;
            if (s.xy) {
                const glm::dvec2 x(p.x, p.y);
                const double b0 = orient({b.x, b.y}, {c.x, c.y}, x) / area;
                const double b1 = orient({c.x, c.y}, {a.x, a.y}, x) / area;
                dev = std::abs(p.z - (b0 * a.z + b1 * b.z + (1.0 - b0 - b1) * c.z));
            } else {
                dev = std::abs(glm::dot(p - a, normal)) / glm::length(normal);
            }
            stats.max_vertical = std::max(stats.max_vertical, dev);
            stats.max_weighted =
                std::max(stats.max_weighted, weighted(s, std::uint32_t(node), dev));
            if (s.has_view && s.view.in_frustum(p))
                stats.max_screen_px =
                    std::max(stats.max_screen_px, dev * k / glm::length(p - s.view.eye));
        };
        if (s.grid_w > 0)
            scan_lattice(
                s, node_of(s, va), node_of(s, vb), node_of(s, vc),
                [](const glm::dvec2 &, const glm::dvec2 &) { return 0.0; },
                [&](std::uint32_t v, const Mesh::Point &, double) {
                    add(std::int32_t(v));
                    return true;
                });
        else
            for (; u >= 0; u = s.next_swallowed[u])
                add(u);
    }
    return stats;
}

static std::size_t block_bytes(const NodeEraser::Impl &s) {
    std::size_t bytes = s.block_cell_scratch.capacity() + s.block_order_scratch.capacity() * 4 +
                        s.tile_z.capacity() * sizeof(float);
    for (const auto &[face, tiles] : s.face_tiles)
        bytes += sizeof(face) + sizeof(tiles) + tiles.capacity() * sizeof(float) + 16;
    for (const auto &[face, blocks] : s.face_blocks)
        bytes += sizeof(face) + sizeof(blocks) + blocks.capacity() * sizeof(Block) + 16;
    for (const auto &[node, kept] : s.kept_fans) {
        bytes += sizeof(node) + sizeof(kept) + 16 + kept.head.capacity() * 4 +
                 kept.maxdev.capacity() * 4 + kept.tiles.capacity() * sizeof(kept.tiles[0]);
        for (const std::vector<float> &tiles : kept.tiles)
            bytes += tiles.capacity() * sizeof(float);
    }
    return bytes;
}

std::size_t NodeEraser::history_bytes() const {
    const Impl &s = *impl_;
    return s.face_maxdev.capacity() * 4 + s.next_swallowed.capacity() * 4 +
           s.face_head.capacity() * 4 + s.face_blocked.capacity() + s.block_scratch.capacity() * 4 +
           block_bytes(s) + s.record_of.capacity() * 4 + s.flags.capacity() + s.stamp.capacity() +
           s.heap.bytes() + s.weight.capacity() * sizeof(float) +
           s.live_list.capacity() * sizeof(LiveNode) + s.cells.capacity() * sizeof(Cell) +
           s.cell_visit.capacity() + s.records.bytes() + s.ring_pool.bytes() +
           (s.regular ? s.regular->bytes() : 0) + s.free_edges.capacity() * sizeof(EH) +
           s.free_faces.capacity() * sizeof(FH) + s.free_vertices.capacity() * sizeof(VH) +
           s.face_seen_dev.capacity() * 4 + s.face_seen.capacity() * 4 + sizeof(s.seen_views) +
           s.sample_of.capacity() * sizeof(std::uint32_t) +
           (s.lattice_x.capacity() + s.lattice_y.capacity()) * sizeof(float) +
           s.swallowed_by.capacity() * 4;
}

EraseStats erase_nodes(Mesh &mesh, const View *view, const EraseOptions &options) {
    EraseStats stats;
    {
        NodeEraser eraser(mesh, view, options);
        stats = eraser.erase();
    }
    Stopwatch clock;
    mesh.garbage_collection();
    stats.ms += clock.ms();
    return stats;
}

// Whether greedy insertion to options.max_error likely ends under options.max_nodes and pays: the
// insertion on every k_probe_step-th sample of each row and column keeps at most k_probe_share of
// those samples. The insertion's cost grows with its nodes where the erase's grows with the
// samples, so only a bound coarse enough for the terrain pays. Scratch runs, the seeded insertion
// and the erase after it against the erase from the grid (time ratio; the probe's share; the
// insertion's share of all samples):
//   N42E001  20 m 0.3x (64 %, 12 %), 10 m 0.5x (81 %, 26 %), 5 m 0.8x (90 %, 48 %),
//            2 m 1.2x (96 %, 76 %), 1 m 1.8x (97 %, 90 %);
//   Rainier  20 m (51 %, 9 %), 10 m (70 %, 20 %), 5 m 0.7x (84 %, 39 %), 2 m 1.1x (94 %, 69 %),
//            1 m 1.5x (96 %, 86 %).
// The probe takes 40-80 ms. One that misjudges costs the insertion up to max_nodes.
static bool greedy_pays(const Heightfield &hf, const GreedyOptions &options) {
    constexpr int k_probe_step = 4;
    constexpr double k_probe_share = 0.92;
    Heightfield probe;
    probe.width = (hf.width - 1) / k_probe_step + 1;
    probe.height = (hf.height - 1) / k_probe_step + 1;
    if (probe.width < 16 || probe.height < 16)
        return true; // too small to tell, and cheap either way
    probe.dx = hf.dx * k_probe_step;
    probe.dy = hf.dy * k_probe_step;
    probe.z.reserve(std::size_t(probe.size()));
    for (int r = 0; r < probe.height; ++r)
        for (int c = 0; c < probe.width; ++c)
            probe.z.push_back(hf.at(c * k_probe_step, r * k_probe_step));
    GreedyOptions po = options;
    po.max_nodes = std::int64_t(k_probe_share * double(probe.size()));
    return !greedy_tin(probe, po).stopped;
}

Mesh erase_dem(const Heightfield &hf, const View *view, const EraseOptions &options,
               const DemEraseOptions &dem, DemEraseStats *stats) {
    Stopwatch clock;
    DemEraseStats out;
    const bool budget = options.max_nodes > 0;
    // With a budget: the retrieval's nodes, at most half of the samples, and then only when that
    // leaves the erase at least 3/4 of budget_share times the budget to choose from. A retrieval
    // cut to fewer is coarse where the erase cannot mend it: a 129² DEM to 23 % of its samples
    // kept 2.2 times the budget at 2 px, which the output then showed (1.97 px, where the erase
    // from the whole grid reaches 1.03).
    const double target =
        std::min(dem.budget_share * double(options.max_nodes), 0.5 * double(hf.size()));
    const bool retrieve =
        view && options.significance.model == SpModel::screen &&
        (budget ? dem.budget_share > 0.0 &&
                      target >= 0.75 * dem.budget_share * double(options.max_nodes)
                : dem.retrieve_share > 0.0);
    const auto build = [&]() -> Mesh {
        if (!retrieve) {
            out.retrieved_nodes = hf.size();
            return grid_tin(hf);
        }
        std::optional<QuadTree> own;
        if (!dem.tree)
            own.emplace(hf);
        QuadTreeLod lod(dem.tree ? *dem.tree : *own);
        const View &eye = *view;
        RetrieveOptions ro;
        ro.peripheral = &options.significance;
        const double shared =
            std::isfinite(options.tolerance) ? options.tolerance * dem.retrieve_share : INFINITY;
        ro.tol_px = shared;
        const Retrieval *r = nullptr; // the last retrieval (it lives until the next one)
        if (budget && shared > 1e-6) {
            // A tolerance that keeps (1, 1.2] x the target, never over the tolerance's share (a
            // budget and a bound: the bound holds). The node count falls about as a power of the
            // tolerance, so each step aims at 1.1 x the target along the slope of the last two
            // retrievals in log-log (the first along -1), and bisects the bracket on the log when
            // a step would leave it: 3-5 retrievals where bisection from [1e-6, 1e6] took 10-15.
            double lo = 1e-6, hi = std::min(1e6, shared);
            double t = std::min(1.0, hi), slope = -1.0, last_t = 0.0, last_n = 0.0;
            for (int i = 0; i < 40; ++i) {
                ro.tol_px = t;
                r = &lod.retrieve(eye, ro);
                const double n = double(r->nodes.size());
                (n > target ? lo : hi) = t;
                if (n > target && n <= 1.2 * target)
                    break;
                if (last_t > 0.0 && n != last_n)
                    slope = std::clamp(std::log(n / last_n) / std::log(t / last_t), -4.0, -0.25);
                last_t = t;
                last_n = n;
                t *= std::exp(std::log(1.1 * target / n) / slope);
                if (!(t > lo && t < hi))
                    t = std::sqrt(lo * hi);
            }
            const double last = ro.tol_px;
            ro.tol_px = std::min(lo, shared);
            if (ro.tol_px != last)
                r = nullptr;
        }
        if (!r)
            r = &lod.retrieve(eye, ro);
        out.retrieved_nodes = std::int64_t(r->nodes.size());
        out.retrieve_tol = ro.tol_px;
        return to_sparse_lattice_mesh(*r, hf);
    };
    // A retrieval's or an insertion's TIN holds vertices for its samples only (the lattice gives
    // the eraser the others' heights), the full grid one per sample.
    const auto erase = [&](Mesh &mesh, FirstStage stage) {
        out.first_stage = stage;
        out.retrieve_ms = clock.ms();
        EraseOptions eo = options;
        eo.lattice = stage == FirstStage::grid ? nullptr : &hf;
        out.erase = NodeEraser(mesh, view, eo).erase();
        clock.reset();
        Mesh tin = live_copy(mesh);
        out.erase.ms += clock.ms();
        if (stats)
            *stats = out;
        return tin;
    };
    // The vertical model with a bound: greedy insertion to the bound, then the erase, when the
    // insertion keeps few enough samples for that to be faster than the erase from the grid. The
    // insertion counts the erase's rounding margin (for the float coordinates farthest from the
    // origin, twice: the erase measures at rounded points), so its TIN is within the bound as the
    // erase measures it.
    if (options.significance.model == SpModel::vertical && std::isfinite(options.tolerance) &&
        options.tolerance > 0.0 && !budget && dem.greedy_cap > 0.0) {
        GreedyOptions go;
        go.max_error = options.tolerance;
        go.max_nodes = std::int64_t(dem.greedy_cap * double(hf.size()));
        go.slope_margin =
            2.0 * rounding_margin(std::max((hf.width - 1) * hf.dx, (hf.height - 1) * hf.dy), 1.0);
        go.seed_step = 16; // the erase drops the seed's nodes the insertion did not need
        if (greedy_pays(hf, go)) {
            const GreedyTin greedy = greedy_tin(hf, go);
            if (!greedy.stopped) {
                Mesh mesh = to_sparse_lattice_mesh(greedy.tin, hf);
                out.retrieved_nodes = std::int64_t(greedy.tin.nodes.size());
                out.retrieve_tol = options.tolerance;
                return erase(mesh, FirstStage::greedy);
            }
        }
    }
    Mesh mesh = build();
    return erase(mesh, retrieve ? FirstStage::quadtree : FirstStage::grid);
}

// ---- Public ring geometry ----------------------------------------------------------------------

RingOrientation ring_orientation(std::span<const glm::dvec2> ring) {
    double area2 = 0.0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const glm::dvec2 &a = ring[i];
        const glm::dvec2 &b = ring[(i + 1) % ring.size()];
        area2 += a.x * b.y - b.x * a.y;
    }
    return area2 > 0.0   ? RingOrientation::ccw
           : area2 < 0.0 ? RingOrientation::cw
                         : RingOrientation::degenerate;
}

std::vector<int> order_ring(const glm::dvec2 &centre, std::span<const glm::dvec2> neighbours) {
    std::vector<int> order(neighbours.size());
    std::iota(order.begin(), order.end(), 0);
    std::vector<double> angle(neighbours.size());
    for (std::size_t i = 0; i < neighbours.size(); ++i)
        angle[i] = std::atan2(neighbours[i].y - centre.y, neighbours[i].x - centre.x);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return angle[a] < angle[b]; });
    return order;
}

bool is_erasable_ear(std::span<const glm::dvec2> ring, int i) {
    const int n = int(ring.size());
    if (n < 3 || n > k_max_ring)
        return false;
    std::array<std::uint8_t, k_max_ring> next;
    for (int j = 0; j < n; ++j)
        next[j] = std::uint8_t((j + 1) % n);
    return ear_quality(ring.data(), next.data(), (i + n - 1) % n, i, (i + 1) % n) >= 0.0;
}

std::vector<RingTriangle> triangulate_ring(std::span<const glm::dvec2> ring) {
    std::array<RingTriangle, k_max_ring> out;
    const int count = clip_ears(ring.data(), int(ring.size()), out.data());
    if (count < 0)
        return {};
    return {out.begin(), out.begin() + count};
}

} // namespace tinlod
