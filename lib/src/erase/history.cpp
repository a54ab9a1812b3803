// The history of the erases (history.hpp) and NodeEraser's recovery and compaction.
#include "erase/history.hpp"

#include "erase/edits.hpp"
#include "erase/lattice_scan.hpp"
#include "erase/swallowed.hpp"

#include <algorithm>
#include <functional>

namespace tinlod::erase {

void record_absent_samples(const Input &input, LiveSet &live, History &history,
                           bool retrieval_tin) {
    live.flags.assign(input.nodes, 0);
    const auto height = input.nodes / input.grid_w;
    history.regular = std::make_unique<RegularRings>(input.grid_w, height);
    if (retrieval_tin && RegularRings::regular_for_retrievals(input.grid_w, height)) {
        for (std::size_t x = 0; x < history.record_of.size(); ++x)
            if (history.record_of[x] == k_absent) {
                live.flags[x] = k_unread;
                history.record_of[x] = k_regular_ring;
            }
        return;
    }
    absent_sample_rings(*input.mesh, input.grid_w, height, input.sample_of,
                        [&](std::uint32_t x, const std::uint32_t *ring, int n, bool boundary) {
                            live.flags[x] = k_unread;
                            std::array<std::uint32_t, 4> regular;
                            bool chain = false;
                            if (history.regular->ring(x, regular.data(), chain) == n &&
                                chain == boundary && std::equal(ring, ring + n, regular.data())) {
                                history.record_of[x] = k_regular_ring;
                                return;
                            }
                            const std::size_t k = history.records.append(1);
                            EraseRecord &record = history.records[k];
                            record.ring_begin =
                                std::uint32_t(history.ring_pool.append(std::size_t(n)));
                            record.ring_size = record.ring_capacity = std::uint8_t(n);
                            record.boundary = boundary;
                            std::copy(ring, ring + n, &history.ring_pool[record.ring_begin]);
                            history.record_of[x] = std::int32_t(k);
                        });
}

void swallow_absent(EraserState &s) {
    const Mesh &m = *s.input.mesh;
    for (auto f : m.faces()) {
        const HH he = m.halfedge_handle(f);
        const std::array<VH, 3> v = {m.from_vertex_handle(he), m.to_vertex_handle(he),
                                     m.to_vertex_handle(m.next_halfedge_handle(he))};
        const std::array<std::uint32_t, 3> ids = {node_of(s, v[0]), node_of(s, v[1]),
                                                  node_of(s, v[2])};
        // A vertex's point is its node's (bind_nodes checked it): read, not made from the lattice.
        std::array<glm::dvec3, 3> p;
        for (int k = 0; k < 3; ++k)
            p[k] = to_glm(m.point(v[k]));
        const TriangleFrame frame = triangle_frame(glm::dvec2(p[0]), glm::dvec2(p[1]),
                                                   glm::dvec2(p[2]), true, p[0].z, p[1].z, p[2].z);
        const auto [maxdev, worst] = face_worst(s, ids[0], ids[1], ids[2], frame, p[0], p[1], p[2]);
        s.faces.face_head[f.idx()] = worst;
        s.faces.face_maxdev[f.idx()] = maxdev;
        constexpr RingTriangle corners{0, 1, 2};
        if (worst >= 0)
            widen_fans(s, p.data(), ids.data(), 3, &corners, &maxdev, 1);
    }
}

namespace {

// Recovers x and the erases it depends on; appends every node re-inserted to `done`.
static std::int64_t recover_closure(EraserState &s, std::uint32_t v,
                                    std::vector<std::uint32_t> *done) {
    std::int64_t recovered = 0;
    std::vector<std::uint32_t> stack{v};
    while (!stack.empty()) {
        const std::uint32_t x = stack.back();
        if (s.history.record_of[x] < 0) {
            stack.pop_back();
            continue;
        }
        std::array<std::uint32_t, 4> scratch;
        const ErasedRing ring = erased_ring(s.history, x, scratch);
        bool ready = true;
        for (int i = 0; i < ring.size; ++i) {
            const std::uint32_t u = ring.nodes[i];
            if (s.history.record_of[u] >= 0) {
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

} // namespace

} // namespace tinlod::erase

namespace tinlod {

using namespace erase;

std::int64_t NodeEraser::recover(Mesh::VertexHandle v) {
    return recover_closure(*state_, node_of(*state_, v), nullptr);
}

std::int64_t NodeEraser::recover_all() {
    EraserState &s = *state_;
    // The records from the last made to the first (a one-off erase undone in reverse: no closure
    // to walk).
    std::vector<std::pair<std::int32_t, std::uint32_t>> erased;
    for (std::uint32_t x = 0; x < std::uint32_t(s.history.record_of.size()); ++x)
        if (s.history.record_of[x] >= 0)
            erased.emplace_back(s.history.record_of[x], x);
    std::sort(erased.begin(), erased.end(), std::greater<>());
    std::int64_t recovered = 0;
    for (const auto &[record, x] : erased)
        recovered += recover_closure(s, x, nullptr);
    return recovered;
}

bool NodeEraser::is_erased(Mesh::VertexHandle v) const {
    return state_->history.record_of[node_of(*state_, v)] >= 0;
}

ErasedNodeRing NodeEraser::ring(Mesh::VertexHandle v) const {
    assert(is_erased(v));
    std::array<std::uint32_t, 4> scratch;
    const ErasedRing ring = erased_ring(state_->history, node_of(*state_, v), scratch);
    return {{ring.nodes, ring.nodes + ring.size}, ring.boundary};
}

} // namespace tinlod

namespace tinlod::erase {

void compact(EraserState &s) {
    Mesh &m = *s.input.mesh;
    // The per-face state rides along as face properties while the collection moves the faces.
    OpenMesh::FPropHandleT<float> maxdev;
    OpenMesh::FPropHandleT<std::int32_t> head;
    m.add_property(maxdev);
    m.add_property(head);
    m.property(maxdev).data_vector() = std::move(s.faces.face_maxdev);
    m.property(head).data_vector() = std::move(s.faces.face_head);
    // A sparse lattice's erased vertices go too (its erased nodes have none): each live node's
    // vertex is found again from the origin property, which the collection moves with it.
    m.garbage_collection(s.input.lattice != nullptr, true, true);
    if (s.input.lattice) {
        std::vector<VH>().swap(s.history.free_vertices);
        s.input.sample_of.resize(m.n_vertices());
        s.input.sample_of.shrink_to_fit();
        for (auto v : m.vertices()) {
            const std::uint32_t x = std::uint32_t(m.property(s.input.origin, v));
            s.input.sample_of[std::size_t(v.idx())] = x;
            live_node(s, x).vertex = v.idx();
        }
    }
    s.faces.face_maxdev = std::move(m.property(maxdev).data_vector());
    s.faces.face_head = std::move(m.property(head).data_vector());
    for (std::size_t f = 0; f < s.faces.face_head.size() && s.input.grid_w == 0; ++f)
        for (std::int32_t u = s.faces.face_head[f]; u >= 0;
             u = s.faces.next_swallowed[std::size_t(u)])
            s.faces.swallowed_by[std::size_t(u)] = std::int32_t(f); // the faces moved
    m.remove_property(maxdev);
    m.remove_property(head);
    s.faces.face_maxdev.shrink_to_fit();
    s.faces.face_head.shrink_to_fit();
    if (s.follower)
        s.follower->faces_compacted(s.faces.face_head.size());
    // With the list's room, so that they grow with it.
    s.live.slot_key.reserve(s.live.list.capacity());
    s.live.slot_stamp.reserve(s.live.list.capacity());
    s.live.slot_key.resize(s.live.list.size());
    s.live.slot_stamp.resize(s.live.list.size());
    for (std::size_t i = 0; i < s.live.list.size(); ++i) {
        s.live.slot_key[i] = s.live.heap.key(s.live.list[i].node);
        s.live.slot_stamp[i] = s.live.stamp[s.live.list[i].node];
    }
    s.live.heap.release();
    std::vector<std::uint8_t>().swap(s.live.stamp);
    s.live.node_keys = true;
    std::vector<float>().swap(s.weights.per_vertex); // and compute weights where they need them
    std::vector<EH>().swap(s.history.free_edges);
    std::vector<FH>().swap(s.history.free_faces);
    s.history.records.shrink_to_fit();
    s.history.ring_pool.shrink_to_fit();
}

} // namespace tinlod::erase

namespace tinlod {

std::size_t NodeEraser::history_bytes() const { return state_->bytes(); }

} // namespace tinlod
