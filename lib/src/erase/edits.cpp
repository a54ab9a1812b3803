// The erase and re-insert edits (edits.hpp).
#include "erase/edits.hpp"

#include "erase/lattice_scan.hpp"
#include "erase/swallowed.hpp"

#include <algorithm>

namespace tinlod::erase {

void retriangulate(EraserState &s) {
    Hole &h = s.scratch.hole;
    Mesh &m = *s.input.mesh;
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
    if (s.input.lattice)
        s.history.free_vertices.push_back(h.v);
    for (int i = next_spoke; i < n; ++i) {
        const EH e = m.edge_handle(h.h[i]);
        m.status(e).set_deleted(true);
        s.history.free_edges.push_back(e);
    }
    const std::uint32_t x = node_of(s, h.v);
    if (s.follower)
        s.follower->fan_erasing(s, x, h, face.data(), fans);
    for (int t = 0; t < fans; ++t) {
        s.faces.face_head[face[t].idx()] = -1;
        face_changed(s.follower, face[t]);
        s.faces.face_maxdev[face[t].idx()] = 0.0f;
    }
    for (int t = h.ntri; t < fans; ++t) {
        m.status(face[t]).set_deleted(true);
        s.history.free_faces.push_back(face[t]);
    }
    if (s.input.grid_w > 0) {
        for (int t = 0; t < h.ntri; ++t) {
            s.faces.face_head[face[t].idx()] = h.tri_worst[t];
            s.faces.face_maxdev[face[t].idx()] = h.tri_maxdev[t];
        }
    } else {
        for (const Assignment &a : s.scratch.assign)
            push_swallowed(s.faces, face[a.triangle].idx(), a.node, a.dev);
    }
    std::array<float, k_max_ring> tri_dev;
    for (int t = 0; t < h.ntri; ++t)
        tri_dev[t] = s.faces.face_maxdev[face[t].idx()];

    // A node erased before re-uses its record, and its ring's room in the pool when the ring
    // fits: the history stays within one record per node however long the flight.
    std::int32_t k = live_node(s, x).last_record;
    if (k < 0)
        k = std::int32_t(s.history.records.append(1));
    EraseRecord &record = s.history.records[std::size_t(k)];
    if (record.ring_capacity < n) {
        record.ring_begin = std::uint32_t(s.history.ring_pool.append(std::size_t(n)));
        record.ring_capacity = std::uint8_t(n);
    }
    record.ring_size = std::uint8_t(n);
    record.boundary = h.boundary;
    std::array<std::uint32_t, k_max_ring> ids;
    for (int i = 0; i < n; ++i)
        ids[i] = s.history.ring_pool[record.ring_begin + std::size_t(i)] = node_of(s, h.r[i]);
    remove_live(s.live, s.history, s.follower, x, k);
    widen_fans(s, h.p.data(), ids.data(), n, h.tri.data(), tri_dev.data(), h.ntri);
    --s.live.count;
    s.live.faces -= fans - h.ntri;
}

namespace {

// A free edge for a re-insert: one an erase freed, or a new one once compact() dropped them.
static EH take_edge(EraserState &s) {
    if (s.history.free_edges.empty())
        return s.input.mesh->edge_handle(s.input.mesh->new_edge(VH(), VH()));
    const EH e = s.history.free_edges.back();
    s.history.free_edges.pop_back();
    return e;
}

static FH take_face(EraserState &s) {
    if (s.history.free_faces.empty()) {
        s.faces.face_head.push_back(-1);
        s.faces.face_maxdev.push_back(0.0f);
        if (s.follower)
            s.follower->face_added();
        return s.input.mesh->new_face();
    }
    const FH f = s.history.free_faces.back();
    s.history.free_faces.pop_back();
    return f;
}

// The vertex of erased node x: its own without a lattice, else one an erase freed or a new one,
// given x's point and sample (marked deleted, without edges, as erased nodes are).
static VH vertex_for(EraserState &s, std::uint32_t x) {
    if (!s.input.lattice)
        return VH(int(x));
    Mesh &m = *s.input.mesh;
    VH v;
    if (s.history.free_vertices.empty()) {
        v = m.add_vertex(node_point(s, x));
        m.status(v).set_deleted(true);
        s.input.sample_of.push_back(x);
    } else {
        v = s.history.free_vertices.back();
        s.history.free_vertices.pop_back();
        m.point(v) = node_point(s, x);
        s.input.sample_of[std::size_t(v.idx())] = x;
    }
    m.property(s.input.origin, v) = std::int64_t(x);
    return v;
}

} // namespace

void reinsert(EraserState &s, std::uint32_t x) {
    Mesh &m = *s.input.mesh;
    std::array<std::uint32_t, 4> scratch;
    const ErasedRing erased = erased_ring(s.history, x, scratch);
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
    // x is under a face outside its ring when a recovery filed it there (see
    // FaceIndex::swallowed_by): left in that list, the live node would be taken for an erased one
    // (its recovery, its next erase's list).
    if (s.input.grid_w == 0) {
        const std::int32_t by = s.faces.swallowed_by[x];
        if (std::none_of(face.begin(), face.begin() + n_faces, [&](FH f) { return f.idx() == by; }))
            unlink_swallowed(s.faces, s.follower, by, x);
    }

    std::vector<std::uint32_t> &swallowed = s.scratch.swallowed_scratch;
    const std::size_t swallowed_begin = swallowed.size();
    for (int k = 0; k < n_faces; ++k) {
        if (s.input.grid_w == 0)
            for (std::int32_t u = s.faces.face_head[face[k].idx()]; u >= 0;
                 u = s.faces.next_swallowed[u])
                if (std::uint32_t(u) != x)
                    swallowed.push_back(std::uint32_t(u));
        s.faces.face_head[face[k].idx()] = -1;
        face_changed(s.follower, face[k]);
        s.faces.face_maxdev[face[k].idx()] = 0.0f;
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
    if (s.live.flags[x] & k_unread) {
        s.live.flags[x] &= std::uint8_t(~k_unread);
        ++s.counters.entered;
    }

    // Swallowed nodes go back to the fan face that covers them.
    Hole &h = s.scratch.hole;
    h.v = v;
    h.n = n + 1;
    h.boundary = boundary;
    const glm::dvec3 pv = to_glm(m.point(v));
    for (int i = 0; i < n; ++i)
        h.p[i] = to_glm(m.point(vh(s, ring[i])));
    h.p[n] = pv;
    if (s.input.xy) {
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
    frame_triangles(h, s.input.xy);
    if (s.follower && s.follower->fan_restoring(s.faces, x, face.data(), fans)) {
        ++s.counters.fans_kept; // the fan's faces are the triangles they were at the erase
    } else if (s.input.grid_w > 0) {
        for (int i = 0; i < fans; ++i) {
            const std::uint32_t a = ring[i], b = ring[(i + 1) % n];
            const auto [maxdev, worst] =
                face_worst(s, x, a, b, h.frame[i], pv, h.p[i], h.p[(i + 1) % n]);
            s.faces.face_head[face[i].idx()] = worst;
            s.faces.face_maxdev[face[i].idx()] = maxdev;
        }
    }
    for (std::size_t k = swallowed_begin; k < swallowed.size(); ++k) {
        const std::uint32_t u = swallowed[k];
        double dev = 0.0;
        const FH f = face[locate(h, s.input.xy, to_glm(node_point(s, u)), dev)];
        push_swallowed(s.faces, f.idx(), u, float(dev));
    }
    swallowed.resize(swallowed_begin);
    add_live(s, x, s.history.record_of[x] == k_regular_ring ? -1 : s.history.record_of[x], v);
    // Its key from before its erase says nothing of the fan it has now (an infinite one kept the
    // update's pick from ever re-evaluating it).
    if (s.live.node_keys || s.live.heap.has_key(x))
        store_node_key(s, x, 0.0f);
    std::array<float, k_max_ring> tri_dev;
    for (int i = 0; i < fans; ++i)
        tri_dev[i] = s.faces.face_maxdev[face[i].idx()];
    std::array<std::uint32_t, k_max_ring + 1> ids;
    std::copy(ring, ring + n, ids.begin());
    ids[n] = x;
    widen_fans(s, h.p.data(), ids.data(), n + 1, h.tri.data(), tri_dev.data(), fans);
    ++s.live.count;
    s.live.faces += fans - (n - 2);
}

} // namespace tinlod::erase
