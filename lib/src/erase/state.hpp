// The eraser's state (EraserState) and its small, hot accessors, inline so that every stage that
// reads a node, its point or its key pays no call: node ids and vertices, the live set, the keys.
#pragma once

#include "erase/containers.hpp"
#include "erase/follower.hpp"
#include "erase/hole_geometry.hpp"
#include "erase/tuning.hpp"
#include "lattice_rings.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/screen_weight.hpp"
#include "tinlod/view.hpp"

#include <array>
#include <cassert>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace tinlod::erase {

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

// A live node. The bounds only the refiner's updates read are not here but in its parallel array
// (refine::FanBounds, kept up through EraserState::follower), so a one-off erase neither carries
// nor maintains them.
struct LiveNode {
    std::uint32_t node;
    std::int32_t vertex; // its vertex (the node id itself unless Input::lattice)
    // The node whose deviation gave the last evaluated cost: here, not in FanBounds, as every
    // evaluation (a one-off erase's too) tries it first (see measure_hole).
    std::uint32_t star;
    std::int32_t last_record; // the node's record from an earlier erase, -1 if none
};

constexpr std::uint8_t k_locked = 1;    // never erased (corner, general-mesh boundary, isolated)
constexpr std::uint8_t k_dirty = 2;     // its key predates a change of its neighbourhood
constexpr std::uint8_t k_recovered = 4; // recovered by the update under way
constexpr std::uint8_t k_unread = 8;    // a sample the input TIN left out, never live yet

constexpr std::int32_t k_absent = -1; // record_of of a sample the input TIN never held
// record_of of a sample left out whose ring is its lattice's regular one (RegularRings): no record.
constexpr std::int32_t k_regular_ring = std::numeric_limits<std::int32_t>::max();

// What only the refiner sets on an eraser (see EraserAccess::make): the public EraseOptions keeps
// what a one-off erase's user sets.
struct HistoryOptions {
    // Erase in passes of independent nodes (no two erased in one pass share a triangle), so every
    // chain of recover dependencies is at most as long as the passes: for a history that will be
    // recovered from (the refiner). Otherwise a pass may erase a node right after its neighbour,
    // which gives fewer nodes, faster, but chains along a row that a recover must undo whole.
    bool shallow_history = false;
    // A grid TIN holding only some of its lattice's samples (to_lattice_mesh): give the samples
    // it left out erase records, as if the erases had taken them from the whole grid in the
    // quad-tree's order (absent_sample_rings), so recover() and the refiner's updates bring them
    // in by local edits like any erased node. A record is kept only where the ring is not the
    // lattice's regular one (RegularRings: none on a 2^k + 1 grid, about half of 1201 x 1201),
    // 20-24 bytes each. Otherwise they never enter.
    bool absent_history = false;
    // With absent_history: the TIN is a quad-tree retrieval's (to_lattice_mesh of retrieve). On a
    // square 2^k + 1 grid every ring of a sample it left out is then the regular one (each leaf's
    // fan holds its centre, and each sample enters on the edge RegularRings names), so the
    // constructor takes them from the lattice without replaying the insertions
    // (docs/decisions/019-erase-dem-first-stage.md). Other sizes replay as without it.
    bool retrieval_tin = false;
};

// The eraser's parts. Each states its invariants and counts its heap memory (bytes(): capacities,
// as NodeEraser::history_bytes reports them). A stage takes the parts it reads and writes; the hot
// accessors below (vh, node_of, node_point) and the stages that need nearly every part take the
// whole EraserState.

// The input: the mesh, the options, node ids.
// Invariants: node ids are 0..nodes-1: a sparse lattice's samples (lattice set), else the mesh's
// vertex indices (sample_of empty). With a lattice, sample_of has an entry per vertex of the mesh
// (the sample it holds), lattice_x / lattice_y the columns' x and rows' y as the mesh's float
// points have them, and inverse_width = 1 / lattice->width. grid_w > 0 exactly for a grid TIN
// (xy projection, see grid_width), the lattice's width.
struct Input {
    Mesh *mesh = nullptr; // borrowed from the caller
    EraseOptions options;
    HistoryOptions history;
    bool xy = true;
    std::uint32_t nodes = 0; // node ids: the lattice's samples, else the mesh's vertices
    // A grid TIN (see grid_width): the lattice's width. Its faces' swallowed nodes are the samples
    // inside them, scanned row by row: no lists (next_swallowed stays empty), and face_head holds
    // each face's worst sample.
    std::uint32_t grid_w = 0;
    // A sparse grid TIN (EraseOptions::lattice): the lattice's samples, and the columns' x and the
    // rows' y as the mesh's float points have them. Only the live samples have a vertex, in their
    // LiveNode (see vh), and sample_of maps each vertex to its sample; an erase frees its node's
    // vertex (History::free_vertices) for the next sample that enters or comes back, which takes
    // its point from here. Node ids are samples; without a lattice (a dense grid TIN or any mesh)
    // they are vertex indices, and sample_of stays empty.
    const Heightfield *lattice = nullptr;
    std::vector<float> lattice_x, lattice_y;
    double inverse_width = 0.0;
    std::vector<std::uint32_t> sample_of;
    OpenMesh::VPropHandleT<std::int64_t> origin; // a sparse lattice's: its vertices' samples
    double area_per_node = 0.0;                  // xy: the input's bounding-box area over its nodes
    glm::dvec2 lo{0.0}, hi{0.0};                 // the input's extent in xy

    std::size_t bytes() const {
        return sample_of.capacity() * sizeof(std::uint32_t) +
               (lattice_x.capacity() + lattice_y.capacity()) * sizeof(float);
    }
};

// The view and the weights.
// Invariants: weigher is the model's (model, view, significance: the view is meaningful for the
// screen and paper models only), unit_weights exactly for the vertical model; per_vertex is empty
// or has an entry per node, each the weigher at the node rounded up (see weight_of).
struct ViewWeights {
    SpModel model = SpModel::vertical; // set_view's model
    SignificanceOptions significance;  // its parameters
    View view;                         // its view, which update() moves (screen and paper models)
    double focal_distance = 1.0;
    Weigher weigher;          // pixels per unit deviation for the current view
    bool unit_weights = true; // no view, or the vertical model: every weight is 1
    // Per node while erase() runs (it asks for a node's weight again and again): the weigher at
    // the node rounded up, all computed in one run over the vertices when the view is set: the
    // erase asks for most of them, many times each. An update computes each weight where it needs
    // it (as fast there, and 4 bytes per node less to keep;
    // docs/decisions/004-per-vertex-weights.md).
    std::vector<float> per_vertex;

    std::size_t bytes() const { return per_vertex.capacity() * sizeof(float); }
};

// The live set: the live nodes, their keys and flags.
// Invariants: list holds each live node once (History::record_of[x] = -2 - its place, its slot),
// count is its size (a sparse lattice's or a grid TIN's absent samples are not counted) and faces
// the live faces; flags has an entry per node. With node_keys the live nodes' keys and stamps are
// in slot_key and slot_stamp, by slot, and heap and stamp are empty; without it heap's keys and
// stamp have an entry per node, and slot_key and slot_stamp are empty.
struct LiveSet {
    std::vector<LiveNode> list;      // the live nodes, in no order
    std::vector<std::uint8_t> flags; // per node: k_locked, k_dirty, k_recovered, k_unread
    // Per node: the sweep pass (mod 256) that last changed its ring.
    std::vector<std::uint8_t> stamp;
    // Set by compact(): the live nodes' keys and stamps are in slot_key and slot_stamp, and the
    // per-node ones (heap, stamp) are freed, as only an update's sweeps, over live nodes, read
    // them; 5 bytes per input node, and a stamp reset that visits the live nodes, not the terrain.
    // The next erase() goes back to the per-node arrays.
    bool node_keys = false;
    std::vector<float> slot_key;
    std::vector<std::uint8_t> slot_stamp;
    std::uint8_t pass = 0;
    std::size_t chain_cap = 0; // see sweep_node
    NodeHeap heap;
    std::int64_t count = 0, faces = 0; // live nodes, live faces

    std::size_t bytes() const {
        return list.capacity() * sizeof(LiveNode) + flags.capacity() + stamp.capacity() +
               slot_key.capacity() * sizeof(float) + slot_stamp.capacity() + heap.bytes();
    }
};

// The history: one record per erased node.
// Invariants: record_of has an entry per node: an erased node's record (an index into records,
// whose ring is ring_size entries of ring_pool from ring_begin) or k_regular_ring (its ring is
// regular's), k_absent for a sample that can never enter, -2 - its place in LiveSet::list for a
// live node. The free lists hold deleted mesh elements that no live face uses.
struct History {
    // Per node: its erase record (>= 0; k_regular_ring: none, see regular), k_absent for a
    // sample the input TIN never held (see the constructor), or for a live node -2 - its place in
    // LiveSet::list (so an update visits the live nodes without walking the whole terrain).
    std::vector<std::int32_t> record_of;
    ChunkedPool<EraseRecord> records;
    ChunkedPool<std::uint32_t> ring_pool;
    // The samples a grid TIN left out take their rings from here where those are regular (all of
    // them on a 2^k + 1 grid), and keep a record only where not (HistoryOptions::absent_history).
    std::unique_ptr<RegularRings> regular;
    bool absent_for_good = false; // some samples are k_absent: they can never enter
    std::vector<EH> free_edges;
    std::vector<FH> free_faces;
    std::vector<VH> free_vertices; // a sparse lattice's: the vertices its erases freed

    std::size_t bytes() const {
        return record_of.capacity() * 4 + records.bytes() + ring_pool.bytes() +
               (regular ? regular->bytes() : 0) + free_edges.capacity() * sizeof(EH) +
               free_faces.capacity() * sizeof(FH) + free_vertices.capacity() * sizeof(VH);
    }
};

// The face index: each face's swallowed nodes.
// Invariants: face_maxdev and face_head have an entry per face (deleted ones included); a live
// face's swallowed nodes (its list from face_head through next_swallowed, or a grid TIN's samples
// inside it) each deviate at most face_maxdev from it; next_swallowed and swallowed_by have an
// entry per node without a grid (empty with one).
struct FaceIndex {
    std::vector<float> face_maxdev;           // per face: bound on its swallowed nodes' deviation
    std::vector<std::int32_t> next_swallowed; // per node: next node in its face's list
    std::vector<std::int32_t> face_head;      // per face: first swallowed node, -1 none
    // Per node, with the lists: the face whose list holds it. A re-insert takes its node out of
    // that list, wherever it is: on a surface mesh a recovery files a swallowed node by its
    // projection on the recovered node's mean plane, which may put it under a face outside its own
    // ring (see reinsert).
    std::vector<std::int32_t> swallowed_by;

    std::size_t bytes() const {
        return face_maxdev.capacity() * 4 + next_swallowed.capacity() * 4 +
               face_head.capacity() * 4 + swallowed_by.capacity() * 4;
    }
};

// Scratch: what one evaluation or edit leaves for the next to re-use (no invariant across calls;
// hole holds the last evaluation's, which retriangulate reads). Not counted in bytes(): it holds
// one hole's worth.
struct Scratch {
    Hole hole;
    std::vector<Assignment> assign; // swallowed node -> new triangle
    std::vector<std::uint32_t> swallowed_scratch;
};

// Counters over the eraser's life (no heap memory).
struct Counters {
    std::int64_t evaluations = 0;
    std::int64_t entered = 0;   // k_unread samples re-inserted so far
    std::int64_t fans_kept = 0; // re-inserts whose fan faces the follower restored so far
};

// The eraser's state: its parts. NodeEraser holds one.
struct EraserState {
    Input input;
    ViewWeights weights;
    LiveSet live;
    History history;
    FaceIndex faces;
    Counters counters;
    Scratch scratch;
    // The refiner's state, which the edits keep up (follower.hpp); null in a one-off erase.
    Follower *follower = nullptr;

    std::size_t bytes() const {
        return input.bytes() + weights.bytes() + live.bytes() + history.bytes() + faces.bytes();
    }
};

// ---- Node ids and vertices (see Input::lattice) ----

// These three run for most nodes an update touches: inlined wherever they are called
// (docs/decisions/008-inlined-node-lookups.md).

// The vertex of node x: invalid for a sparse lattice's sample that is not live. A live node's is
// in its LiveNode, not in an array over the samples (4 bytes each).
[[gnu::always_inline]] inline VH vh(const EraserState &s, std::uint32_t x) {
    if (!s.input.lattice)
        return VH(int(x));
    const std::int32_t r = s.history.record_of[x];
    return r < -1 ? VH(s.live.list[std::size_t(-2 - r)].vertex) : VH();
}

// The node id of vertex v.
[[gnu::always_inline]] inline std::uint32_t node_of(const EraserState &s, VH v) {
    return s.input.sample_of.empty() ? std::uint32_t(v.idx())
                                     : s.input.sample_of[std::size_t(v.idx())];
}

// The point of node x, live or erased (a sparse lattice's sample has it without a vertex). Its
// row comes from a multiplication by 1 / width, corrected once: a division took most of the
// function's time.
[[gnu::always_inline]] inline Mesh::Point node_point(const EraserState &s, std::uint32_t x) {
    if (!s.input.lattice)
        return s.input.mesh->point(VH(int(x)));
    const auto w = std::uint32_t(s.input.lattice->width);
    auto r = std::uint32_t(double(x) * s.input.inverse_width);
    if (r * w > x)
        --r;
    else if ((r + 1) * w <= x)
        ++r;
    return {s.input.lattice_x[x - r * w], s.input.lattice_y[r], s.input.lattice->z[x]};
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

inline Samples samples(const Input &input) {
    Samples g;
    g.w = input.grid_w;
    if (input.lattice) {
        g.z = input.lattice->z.data();
        g.xs = input.lattice_x.data();
        g.ys = input.lattice_y.data();
    } else {
        g.pts = input.mesh->points();
    }
    return g;
}

// Makes x (vertex v) live; `record` is its record from an earlier erase (-1 if none), kept for
// re-use.
inline void add_live(EraserState &s, std::uint32_t x, std::int32_t record, VH v) {
    const auto slot = std::uint32_t(s.live.list.size());
    s.history.record_of[x] = -2 - std::int32_t(slot);
    s.live.list.push_back({x, v.idx(), x, record});
    if (s.live.node_keys) {
        s.live.slot_key.push_back(0.0f);
        s.live.slot_stamp.push_back(0);
    }
    if (s.follower)
        s.follower->live_added(slot, node_point(s, x));
}

// Live node x's place in LiveSet::list.
inline std::uint32_t live_slot(const EraserState &s, std::uint32_t x) {
    assert(s.history.record_of[x] < -1);
    return std::uint32_t(-2 - s.history.record_of[x]);
}

inline LiveNode &live_node(EraserState &s, std::uint32_t x) { return s.live.list[live_slot(s, x)]; }

// Live node x's key (a lower bound of its cost under the current view; +inf: parked, or no erase
// possible until its ring changes) and its sweep stamp, wherever LiveSet::node_keys keeps them.
inline float node_key(EraserState &s, std::uint32_t x) {
    return s.live.node_keys ? s.live.slot_key[live_slot(s, x)] : s.live.heap.key(x);
}

// The same for the live node in `slot`: without the look-up of its place in the live list (a
// cache miss per node of an update's walks over them).
inline float node_key(const LiveSet &live, std::uint32_t slot) {
    return live.node_keys ? live.slot_key[slot] : live.heap.key(live.list[slot].node);
}

inline void store_node_key(EraserState &s, std::uint32_t x, float key) {
    if (s.live.node_keys)
        s.live.slot_key[live_slot(s, x)] = key;
    else
        s.live.heap.store_key(x, key);
}

inline void store_node_key(LiveSet &live, std::uint32_t slot, float key) {
    if (live.node_keys)
        live.slot_key[slot] = key;
    else
        live.heap.store_key(live.list[slot].node, key);
}

inline std::uint8_t &node_stamp(EraserState &s, std::uint32_t x) {
    return s.live.node_keys ? s.live.slot_stamp[live_slot(s, x)] : s.live.stamp[x];
}

// Face f's swallowed nodes change: the follower's bounds on it go.
inline void face_changed(Follower *follower, FH f) {
    if (follower)
        follower->face_changed(f);
}

// Marks live node x dirty (its key predates a change of its fan).
inline void mark_dirty(EraserState &s, std::uint32_t x) {
    s.live.flags[x] |= k_dirty;
    if (s.follower)
        s.follower->dirtied(live_slot(s, x));
}

// Takes x out of the live set (the last live node takes its slot), `record` its record now.
inline void remove_live(LiveSet &live, History &history, Follower *follower, std::uint32_t x,
                        std::int32_t record) {
    const std::int32_t place = -2 - history.record_of[x];
    const LiveNode last = live.list.back();
    live.list[std::size_t(place)] = last;
    history.record_of[last.node] = -2 - place;
    live.list.pop_back();
    if (live.node_keys) {
        live.slot_key[std::size_t(place)] = live.slot_key.back();
        live.slot_key.pop_back();
        live.slot_stamp[std::size_t(place)] = live.slot_stamp.back();
        live.slot_stamp.pop_back();
    }
    if (follower)
        follower->live_removed(std::uint32_t(place));
    history.record_of[x] = record;
}

// The ring of erased node x's last erase: its record's, or its regular one (written to `scratch`).
struct ErasedRing {
    const std::uint32_t *nodes;
    int size;
    bool boundary;
};

inline ErasedRing erased_ring(const History &history, std::uint32_t x,
                              std::array<std::uint32_t, 4> &scratch) {
    assert(history.record_of[x] >= 0);
    if (history.record_of[x] == k_regular_ring) {
        bool boundary = false;
        const int n = history.regular->ring(x, scratch.data(), boundary);
        return {scratch.data(), n, boundary};
    }
    const EraseRecord &record = history.records[std::size_t(history.record_of[x])];
    return {history.ring_pool.run(record.ring_begin), record.ring_size, record.boundary};
}

} // namespace tinlod::erase

namespace tinlod::erase {

// The refiner's and the internal tests' way into a NodeEraser: one made with the options only the
// refiner sets and its follower, and its state.
struct EraserAccess {
    static NodeEraser make(Mesh &mesh, const Significance &model, const EraseOptions &options,
                           const HistoryOptions &history, Follower *follower) {
        return NodeEraser(mesh, model, options, history, follower);
    }
    static EraserState &state(NodeEraser &eraser) { return *eraser.state_; }
    static const EraserState &state(const NodeEraser &eraser) { return *eraser.state_; }
};

} // namespace tinlod::erase
