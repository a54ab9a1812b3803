// The eraser's state (EraserState) and its small, hot accessors, inline so that every stage that
// reads a node, its point or its key pays no call: node ids and vertices, the live set, the keys.
#pragma once

#include "erase/containers.hpp"
#include "erase/hole_geometry.hpp"
#include "erase/tuning.hpp"
#include "lattice_rings.hpp"
#include "refine/frame_state.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/screen_weight.hpp"
#include "tinlod/view.hpp"

#include <array>
#include <cassert>
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_map>
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

// What an update needs to know of a live node without walking its fan (see NodeEraser::update).
struct LiveNode {
    std::uint32_t node;
    std::int32_t vertex; // its vertex (the node id itself unless Input::lattice)
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
    std::uint32_t cell;       // its cell of the update's grid (UpdateGrid)
    // For the screen model's updates, as logarithms (see ViewBounds::face_seen_dev for the motion
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
    // Once compact() ran (LiveSet::node_keys): the node's key and sweep stamp (see node_key).
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

using refine::Cell;

constexpr std::uint8_t k_locked = 1;    // never erased (corner, general-mesh boundary, isolated)
constexpr std::uint8_t k_dirty = 2;     // its key predates a change of its neighbourhood
constexpr std::uint8_t k_recovered = 4; // recovered by the update under way
constexpr std::uint8_t k_unread = 8;    // a sample the input TIN left out, never live yet

constexpr std::int32_t k_absent = -1; // record_of of a sample the input TIN never held
// record_of of a sample left out whose ring is its lattice's regular one (RegularRings): no record.
constexpr std::int32_t k_regular_ring = std::numeric_limits<std::int32_t>::max();

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
// Invariants: list holds each live node once (History::record_of[x] = -2 - its place), count is
// its size (a sparse lattice's or a grid TIN's absent samples are not counted) and faces the live
// faces; flags has an entry per node. With node_keys the live nodes' keys and stamps are in their
// LiveNode and heap and stamp are empty; without it heap's keys and stamp have an entry per node.
struct LiveSet {
    std::vector<LiveNode> list;      // the live nodes, in no order
    std::vector<std::uint8_t> flags; // per node: k_locked, k_dirty, k_recovered, k_unread
    // Per node: the sweep pass (mod 256) that last changed its ring.
    std::vector<std::uint8_t> stamp;
    // Set by compact(): the live nodes' keys and stamps are in their LiveNode, and the per-node
    // ones (heap, stamp) are freed, as only an update's sweeps, over live nodes, read them; 5
    // bytes per input node, and a stamp reset that visits the live nodes, not the terrain. The
    // next erase() goes back to the per-node arrays.
    bool node_keys = false;
    std::uint8_t pass = 0;
    std::size_t chain_cap = 0; // see sweep_node
    NodeHeap heap;
    std::int64_t count = 0, faces = 0; // live nodes, live faces

    std::size_t bytes() const {
        return list.capacity() * sizeof(LiveNode) + flags.capacity() + stamp.capacity() +
               heap.bytes();
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
    // them on a 2^k + 1 grid), and keep a record only where not (EraseOptions::absent_history).
    std::unique_ptr<RegularRings> regular;
    bool absent_for_good = false; // some samples are k_absent: they can never enter
    // A shallow history's erased nodes whose fan covered more than k_kept_fan_samples samples of a
    // grid TIN: per fan face, what it knew of its samples (see KeptFan), by node.
    std::unordered_map<std::uint32_t, KeptFan> kept_fans;
    std::vector<EH> free_edges;
    std::vector<FH> free_faces;
    std::vector<VH> free_vertices; // a sparse lattice's: the vertices its erases freed

    std::size_t bytes() const {
        std::size_t bytes = record_of.capacity() * 4 + records.bytes() + ring_pool.bytes() +
                            (regular ? regular->bytes() : 0) + free_edges.capacity() * sizeof(EH) +
                            free_faces.capacity() * sizeof(FH) +
                            free_vertices.capacity() * sizeof(VH);
        for (const auto &[node, kept] : kept_fans) {
            bytes += sizeof(node) + sizeof(kept) + 16 + kept.head.capacity() * 4 +
                     kept.maxdev.capacity() * 4 + kept.tiles.capacity() * sizeof(kept.tiles[0]);
            for (const std::vector<float> &tiles : kept.tiles)
                bytes += tiles.capacity() * sizeof(float);
        }
        return bytes;
    }
};

// The face index: each face's swallowed nodes.
// Invariants: face_maxdev, face_head and face_blocked have an entry per face (deleted ones
// included); a live face's swallowed nodes (its list from face_head through next_swallowed, or a
// grid TIN's samples inside it) each deviate at most face_maxdev from it; next_swallowed and
// swallowed_by have an entry per node without a grid (empty with one); face_blocked[f] is 1
// exactly when face_blocks or face_tiles holds f.
struct FaceIndex {
    std::vector<float> face_maxdev;           // per face: bound on its swallowed nodes' deviation
    std::vector<std::int32_t> next_swallowed; // per node: next node in its face's list
    std::vector<std::int32_t> face_head;      // per face: first swallowed node, -1 none
    // Per node, with the lists: the face whose list holds it. A re-insert takes its node out of
    // that list, wherever it is: on a surface mesh a recovery files a swallowed node by its
    // projection on the recovered node's mean plane, which may put it under a face outside its own
    // ring (see reinsert).
    std::vector<std::int32_t> swallowed_by;
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

    std::size_t bytes() const {
        std::size_t bytes = face_maxdev.capacity() * 4 + next_swallowed.capacity() * 4 +
                            face_head.capacity() * 4 + face_blocked.capacity() +
                            tile_z.capacity() * sizeof(float) + swallowed_by.capacity() * 4;
        for (const auto &[face, tiles] : face_tiles)
            bytes += sizeof(face) + sizeof(tiles) + tiles.capacity() * sizeof(float) + 16;
        for (const auto &[face, blocks] : face_blocks)
            bytes += sizeof(face) + sizeof(blocks) + blocks.capacity() * sizeof(Block) + 16;
        return bytes;
    }
};

// Scratch: what one evaluation, edit or face scan leaves for the next to re-use (no invariant
// across calls; hole holds the last evaluation's, which retriangulate reads).
struct Scratch {
    Hole hole;
    std::vector<Assignment> assign; // swallowed node -> new triangle
    std::vector<std::uint32_t> swallowed_scratch;
    std::vector<std::int32_t> block_scratch; // build_blocks' scratch
    std::vector<std::uint8_t> block_cell_scratch;
    std::vector<std::int32_t> block_order_scratch;

    // The blocks' (the others hold one hole's worth).
    std::size_t bytes() const {
        return block_scratch.capacity() * 4 + block_cell_scratch.capacity() +
               block_order_scratch.capacity() * 4;
    }
};

// Counters over the eraser's life (no heap memory).
struct Counters {
    std::int64_t evaluations = 0;
    std::int64_t entered = 0;   // k_unread samples re-inserted so far
    std::int64_t fans_kept = 0; // re-inserts whose fan faces took back a KeptFan so far
};

// The eraser's state: its parts. NodeEraser holds one.
struct EraserState {
    Input input;
    ViewWeights weights;
    LiveSet live;
    History history;
    FaceIndex faces;
    refine::FrameState frame; // the refiner's (refine/frame_state.hpp)
    Counters counters;
    Scratch scratch;

    std::size_t bytes() const {
        return input.bytes() + weights.bytes() + live.bytes() + history.bytes() + faces.bytes() +
               frame.bytes() + scratch.bytes();
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
    const Mesh::Point point = node_point(s, x);
    const glm::dvec3 p = to_glm(point);
    const std::uint32_t c = refine::cell_of(s.frame.grid, p);
    Cell &cell = s.frame.grid.cells[c];
    cell.zlo = std::min(cell.zlo, float_down(p.z));
    cell.zhi = std::max(cell.zhi, float_up(p.z));
    cell.star_dev = 0.0f;
    cell.dirty = true;
    s.history.record_of[x] = -2 - std::int32_t(s.live.list.size());
    LiveNode l{};
    l.node = x;
    l.vertex = v.idx();
    l.p = point;
    l.star = x;
    l.last_record = record;
    l.cell = c;
    s.live.list.push_back(l);
}

inline LiveNode &live_node(EraserState &s, std::uint32_t x) {
    assert(s.history.record_of[x] < 0);
    return s.live.list[std::size_t(-2 - s.history.record_of[x])];
}

// Live node x's key (a lower bound of its cost under the current view; +inf: parked, or no erase
// possible until its ring changes) and its sweep stamp, wherever LiveSet::node_keys keeps them.
inline float node_key(EraserState &s, std::uint32_t x) {
    return s.live.node_keys ? live_node(s, x).key : s.live.heap.key(x);
}

// The same for live node l at hand: without the look-up of its place in the live list (a cache
// miss per node of an update's walks over them).
inline float node_key(const LiveSet &live, const LiveNode &l) {
    return live.node_keys ? l.key : live.heap.key(l.node);
}

inline void store_node_key(EraserState &s, std::uint32_t x, float key) {
    if (s.live.node_keys)
        live_node(s, x).key = key;
    else
        s.live.heap.store_key(x, key);
}

inline void store_node_key(LiveSet &live, LiveNode &l, float key) {
    if (live.node_keys)
        l.key = key;
    else
        live.heap.store_key(l.node, key);
}

inline std::uint8_t &node_stamp(EraserState &s, std::uint32_t x) {
    return s.live.node_keys ? live_node(s, x).stamp : s.live.stamp[x];
}

// Face f's swallowed nodes change: its blocks and its seen bound go.
inline void face_changed(FaceIndex &faces, refine::ViewBounds &seen, FH f) {
    seen.face_seen_dev[f.idx()] = -1.0f;
    if (faces.face_blocked[f.idx()]) {
        faces.face_blocked[f.idx()] = 0;
        faces.face_blocks.erase(f.idx());
        faces.face_tiles.erase(f.idx());
    }
}

// Marks live node x dirty (its key predates a change of its fan).
inline void mark_dirty(EraserState &s, std::uint32_t x) {
    s.live.flags[x] |= k_dirty;
    LiveNode &l = live_node(s, x);
    l.low_log = -INFINITY;
    s.frame.grid.cells[l.cell].dirty = true;
}

inline void remove_live(LiveSet &live, History &history, std::uint32_t x, std::int32_t record) {
    const std::int32_t place = -2 - history.record_of[x];
    const LiveNode last = live.list.back();
    live.list[std::size_t(place)] = last;
    history.record_of[last.node] = -2 - place;
    live.list.pop_back();
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
