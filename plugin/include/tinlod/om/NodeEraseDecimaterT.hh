// tinlod::om::NodeEraseDecimaterT: the paper's node-erase decimater (vertex removal with local
// hole re-triangulation, steps 3-5) in OpenMesh's decimater conventions, for any OpenMesh triangle
// mesh type: initialize(), decimate(n), decimate_to(nv), mesh properties owned for exactly the
// decimater's lifetime, no garbage collection (call mesh.garbage_collection() yourself).
//
// Each vertex's SP is its screen-space significance (significance.hpp): delta = its deviation from
// the re-triangulated hole (vertically for a TIN, from the new triangle's plane otherwise) times
// k / OD * peripheral(OA). The least significant vertex is removed while SP < tolerance; its ring
// is ear-clipped with tinlod::triangulate_ring in the projection plane (xy when every face is
// counter-clockwise in xy, else the fan's mean plane), so there is never a fold-over in that plane
// and never a non-manifold edge; boundary vertices are kept. Ring neighbours are re-scored after
// every removal. Unlike tinlod::NodeEraser (lib/decimate) this scores each removal by the removed
// vertex alone: it carries no whole-output bound and no erase history.
//
// Status attributes: requested in the constructor and released in the destructor (OpenMesh counts
// requests, so a mesh that had them keeps them). Removal uses delete_vertex + add_face.
#pragma once

#include "tinlod/decimate.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/view.hpp"

#include <OpenMesh/Core/Utils/Property.hh>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <vector>

namespace tinlod::om {

template <class MeshT> class NodeEraseDecimaterT {
  public:
    using Mesh = MeshT;
    using VertexHandle = typename MeshT::VertexHandle;

    explicit NodeEraseDecimaterT(MeshT &mesh) : mesh_(mesh) {
        mesh_.request_vertex_status();
        mesh_.request_edge_status();
        mesh_.request_face_status();
        mesh_.add_property(sp_, "tinlod:node_erase:sp");
        mesh_.add_property(version_, "tinlod:node_erase:version");
    }
    ~NodeEraseDecimaterT() {
        mesh_.remove_property(sp_);
        mesh_.remove_property(version_);
        mesh_.release_face_status();
        mesh_.release_edge_status();
        mesh_.release_vertex_status();
    }
    NodeEraseDecimaterT(const NodeEraseDecimaterT &) = delete;
    NodeEraseDecimaterT &operator=(const NodeEraseDecimaterT &) = delete;

    void set_view(const tinlod::View &view) {
        view_ = view;
        has_view_ = true;
    }
    // tau, pixels: vertices whose SP reaches it stay. +inf: only decimate_to's count limits.
    void set_tolerance(double px) { tolerance_ = px; }
    void set_significance(const tinlod::SignificanceOptions &options) { options_ = options; }

    // Scores every vertex; false without a view.
    bool initialize() {
        if (!has_view_)
            return false;
        xy_ = true;
        for (auto fh : mesh_.faces()) {
            glm::dvec3 c[3];
            int i = 0;
            for (auto vh : mesh_.fv_range(fh))
                c[i++] = point(vh);
            xy_ &=
                (c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[2].x - c[0].x) * (c[1].y - c[0].y) > 0.0;
        }
        queue_ = {};
        for (auto vh : mesh_.vertices()) {
            mesh_.property(version_, vh) = 0;
            rescore(vh);
        }
        initialized_ = true;
        return true;
    }

    // Removes up to n vertices (0: every vertex within the tolerance); returns how many.
    std::size_t decimate(std::size_t n = 0) { return run(n == 0 ? SIZE_MAX : n, 0); }

    // Removes vertices until nv live vertices remain (or none is within the tolerance); live =
    // not deleted, so the count is right before garbage_collection(). Returns how many.
    std::size_t decimate_to(std::size_t nv) { return run(SIZE_MAX, nv); }

    // Vertices not deleted.
    std::size_t n_live_vertices() const {
        std::size_t n = 0;
        for (auto vh : mesh_.vertices())
            n += !mesh_.status(vh).deleted();
        return n;
    }

  private:
    struct Hole {
        std::vector<VertexHandle> ring;
        std::vector<tinlod::RingTriangle> triangles;
        double sp = INFINITY;
    };
    struct Entry {
        float sp;
        int vertex;
        std::uint32_t version;
        bool operator>(const Entry &o) const { return sp > o.sp; }
    };

    glm::dvec3 point(VertexHandle vh) const {
        const auto &p = mesh_.point(vh);
        return {p[0], p[1], p[2]};
    }

    // Re-triangulates vh's hole; false when it cannot go (boundary, fold-over, non-manifold).
    bool evaluate(VertexHandle vh, Hole &hole) {
        hole.ring.clear();
        hole.triangles.clear();
        if (mesh_.status(vh).deleted() || mesh_.is_boundary(vh) || !mesh_.is_manifold(vh))
            return false;
        const glm::dvec3 pv = point(vh);
        glm::dvec3 normal(0.0);
        for (auto fh : mesh_.vf_range(vh)) {
            glm::dvec3 c[3];
            int i = 0;
            for (auto u : mesh_.fv_range(fh))
                c[i++] = point(u);
            normal += glm::cross(c[1] - c[0], c[2] - c[0]);
        }
        if (xy_)
            normal = {0.0, 0.0, 1.0};
        const double len = glm::length(normal);
        if (!(len > 0.0))
            return false;
        const glm::dvec3 ez = normal / len;
        const glm::dvec3 helper = std::abs(ez.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        const glm::dvec3 ex = xy_ ? glm::dvec3(1, 0, 0) : glm::normalize(glm::cross(helper, ez));
        const glm::dvec3 ey = glm::cross(ez, ex);
        std::vector<glm::dvec2> q;
        for (auto u : mesh_.vv_range(vh)) {
            hole.ring.push_back(u);
            const glm::dvec3 d = point(u) - pv;
            q.emplace_back(glm::dot(d, ex), glm::dot(d, ey));
        }
        if (hole.ring.size() < 3 || int(hole.ring.size()) > tinlod::k_max_ring)
            return false;
        if (tinlod::ring_orientation(q) == tinlod::RingOrientation::cw) {
            std::reverse(hole.ring.begin(), hole.ring.end());
            std::reverse(q.begin(), q.end());
        }
        const std::size_t n = q.size();
        for (std::size_t i = 0; i < n; ++i) {
            const glm::dvec2 &a = q[i], &b = q[(i + 1) % n];
            if (a.x * b.y - b.x * a.y <= 0.0)
                return false; // the fan is not star-shaped in the projection plane
        }
        hole.triangles = tinlod::triangulate_ring(q);
        if (hole.triangles.empty())
            return false;
        for (const auto &t : hole.triangles)
            for (auto [a, b] : {std::pair{t.a, t.b}, std::pair{t.b, t.c}, std::pair{t.c, t.a}})
                if (std::size_t(b) != (std::size_t(a) + 1) % n &&
                    mesh_.find_halfedge(hole.ring[a], hole.ring[b]).is_valid())
                    return false; // the diagonal exists outside the hole
        // The node's deviation from the new triangle under it.
        double delta = INFINITY;
        for (const auto &t : hole.triangles) {
            const glm::dvec2 &a = q[t.a], &b = q[t.b], &c = q[t.c];
            const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
            const double w0 = (b.x * c.y - c.x * b.y) / area, w1 = (c.x * a.y - a.x * c.y) / area;
            const double w2 = 1.0 - w0 - w1;
            if (std::min({w0, w1, w2}) < -1e-12)
                continue;
            const glm::dvec3 pa = point(hole.ring[t.a]), pb = point(hole.ring[t.b]),
                             pc = point(hole.ring[t.c]);
            const glm::dvec3 nt = glm::cross(pb - pa, pc - pa);
            delta = xy_ ? std::abs(pv.z - (w0 * pa.z + w1 * pb.z + w2 * pc.z))
                        : std::abs(glm::dot(pv - pa, nt)) / std::max(glm::length(nt), 1e-300);
            break;
        }
        if (!std::isfinite(delta))
            return false;
        hole.sp = delta * tinlod::screen_weight(view_, pv, options_);
        return true;
    }

    void rescore(VertexHandle vh) {
        std::uint32_t &version = mesh_.property(version_, vh);
        ++version;
        mesh_.property(sp_, vh) = evaluate(vh, scratch_) ? float(scratch_.sp) : INFINITY;
        if (std::isfinite(mesh_.property(sp_, vh)))
            queue_.push({mesh_.property(sp_, vh), vh.idx(), version});
    }

    std::size_t run(std::size_t max_removals, std::size_t target) {
        if (!initialized_ && !initialize())
            return 0;
        std::size_t live = n_live_vertices(), removed = 0;
        Hole hole;
        while (!queue_.empty() && removed < max_removals && live > target) {
            const Entry e = queue_.top();
            queue_.pop();
            const VertexHandle vh(e.vertex);
            if (mesh_.status(vh).deleted() || mesh_.property(version_, vh) != e.version)
                continue; // superseded by a re-score
            if (!(double(e.sp) < tolerance_))
                break; // the least significant vertex is visible: done
            if (!evaluate(vh, hole))
                continue;
            mesh_.delete_vertex(vh, false);
            for (const auto &t : hole.triangles)
                mesh_.add_face(hole.ring[t.a], hole.ring[t.b], hole.ring[t.c]);
            for (auto u : hole.ring)
                rescore(u);
            ++removed;
            --live;
        }
        return removed;
    }

    MeshT &mesh_;
    OpenMesh::VPropHandleT<float> sp_;
    OpenMesh::VPropHandleT<std::uint32_t> version_;
    tinlod::View view_;
    bool has_view_ = false;
    bool initialized_ = false;
    bool xy_ = true;
    double tolerance_ = 1.0;
    tinlod::SignificanceOptions options_;
    Hole scratch_;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue_;
};

} // namespace tinlod::om
