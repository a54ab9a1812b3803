// tinlod::om::NodeEraseDecimaterT: the library's node erase (tinlod::NodeEraser, decimate.hpp; the
// paper's steps 3-5 with the whole-output bound and the erase history) on any OpenMesh triangle
// mesh type, in OpenMesh's decimater conventions: initialize(), decimate(n), decimate_to(nv),
// deleted flags and no garbage collection (call mesh.garbage_collection() yourself, once the
// decimater is gone), status attributes requested for exactly the decimater's lifetime.
//
// It runs tinlod::NodeEraser on a copy of the mesh in the library's type (the same vertices, in
// order, and the same faces added in the same order, so the same half-edge structure) and writes
// each result back: the faces the erase removed are deleted, the erased vertices marked deleted,
// the new triangles added. So it gives the nodes `tinlod simplify MESH` gives for the same input
// and view, with its guarantees: every input vertex within tolerance pixels of the output surface
// inside the view frustum (relaxed by the peripheral factor outside it, as documented in
// decimate.hpp), its erase order and hole re-triangulation, and recover() back to the input.
// Points are taken as floats, the library's precision.
#pragma once

#include "tinlod/decimate.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
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
    }
    ~NodeEraseDecimaterT() {
        mesh_.release_face_status();
        mesh_.release_edge_status();
        mesh_.release_vertex_status();
    }
    NodeEraseDecimaterT(const NodeEraseDecimaterT &) = delete;
    NodeEraseDecimaterT &operator=(const NodeEraseDecimaterT &) = delete;

    // The observer; the next decimate() erases for it.
    void set_view(const tinlod::View &view) { view_ = view; }
    // tau, pixels: the output keeps every input vertex within it. +inf: only decimate_to's count
    // limits.
    void set_tolerance(double px) { options_.tolerance = px; }
    // The SP model and its parameters (screen by default, as `tinlod simplify`); the screen and
    // paper models erase for the view set_view gives.
    void set_significance(tinlod::SpModel model, const tinlod::SignificanceOptions &options = {}) {
        model_ = model;
        significance_ = options;
    }
    // Every other erase option (projection, max_valence, erase_boundary, ...); the tolerance is
    // taken from it too. max_nodes is set by each call.
    void set_erase_options(const tinlod::EraseOptions &options) { options_ = options; }

    // Copies the mesh's live part into the library's type (decimate() calls it when nobody did) and
    // starts a new history: recover() goes back to the mesh as it is now. False on a mesh that is
    // not all triangles or whose connectivity OpenMesh refuses to copy. The mesh must not change
    // but through this decimater until it is gone.
    bool initialize() {
        eraser_.reset();
        work_ = std::make_unique<tinlod::Mesh>();
        user_vertex_.clear();
        work_vertex_.assign(mesh_.n_vertices(), -1);
        for (auto vh : mesh_.vertices()) {
            const auto &p = mesh_.point(vh);
            work_vertex_[std::size_t(vh.idx())] =
                work_->add_vertex({float(p[0]), float(p[1]), float(p[2])}).idx();
            user_vertex_.push_back(vh);
        }
        for (auto fh : mesh_.faces()) {
            std::vector<tinlod::Mesh::VertexHandle> corners;
            for (auto vh : mesh_.fv_range(fh))
                corners.emplace_back(work_vertex_[std::size_t(vh.idx())]);
            if (corners.size() != 3 || !work_->add_face(corners).is_valid()) {
                work_.reset();
                return false;
            }
        }
        return true;
    }

    // Erases nodes for the view until none can go within the tolerance, or after n erases (0: no
    // limit). Returns how many nodes it erased.
    std::size_t decimate(std::size_t n = 0) {
        const std::size_t live = n_live_vertices();
        return run(n == 0 || n >= live ? 0 : std::int64_t(live - n));
    }

    // Erases nodes until nv live vertices remain or none can go within the tolerance (nv = 0: no
    // count). Returns how many nodes it erased.
    std::size_t decimate_to(std::size_t nv) { return run(std::int64_t(nv)); }

    // Brings every erased node back: the mesh then has the input's vertices and triangles (the
    // triangles as new faces, the old ones marked deleted). Returns how many came back.
    std::size_t recover() {
        if (!eraser_)
            return 0;
        const std::int64_t n = eraser_->recover_all();
        write_back();
        return std::size_t(n);
    }

    // Brings erased vertex vh back, with the erased nodes it depends on. Returns how many came
    // back (0 when vh is live).
    std::size_t recover(VertexHandle vh) {
        if (!eraser_ || !vh.is_valid() || std::size_t(vh.idx()) >= work_vertex_.size() ||
            work_vertex_[std::size_t(vh.idx())] < 0)
            return 0;
        const std::int64_t n =
            eraser_->recover(tinlod::Mesh::VertexHandle(work_vertex_[std::size_t(vh.idx())]));
        write_back();
        return std::size_t(n);
    }

    // The error the last decimate() reached over every erased node (EraseStats: max_screen_px
    // inside the frustum, max_weighted in tolerance units), and its counts (before any erase the
    // write-back had to undo, see failed_faces).
    const tinlod::EraseStats &stats() const { return stats_; }

    // Triangles the last write-back could not add to the mesh, OpenMesh refusing them even after
    // the erases under them were undone: 0 unless the mesh lost its manifold structure.
    std::size_t failed_faces() const { return failed_faces_; }

    // Vertices not deleted.
    std::size_t n_live_vertices() const {
        std::size_t n = 0;
        for (auto vh : mesh_.vertices())
            n += !mesh_.status(vh).deleted();
        return n;
    }

  private:
    // Without a view only the vertical model erases.
    std::size_t run(std::int64_t max_nodes) {
        const bool vertical = model_ == tinlod::SpModel::vertical;
        if ((!view_ && !vertical) || (!work_ && !initialize()))
            return 0;
        tinlod::EraseOptions options = options_;
        options.max_nodes = max_nodes;
        const tinlod::Significance model =
            vertical ? tinlod::Significance::vertical()
                     : tinlod::Significance::of(model_, *view_, significance_);
        if (!eraser_)
            eraser_ = std::make_unique<tinlod::NodeEraser>(*work_, model, options);
        else
            eraser_->set_view(model, options);
        const std::size_t before = n_live_vertices();
        stats_ = eraser_->erase();
        write_back();
        return before - n_live_vertices();
    }

    // The face of the library's mesh with these corners, in this order, is live.
    bool work_has_face(int a, int b, int c) const {
        const tinlod::Mesh &w = *work_;
        using WV = tinlod::Mesh::VertexHandle;
        if (w.status(WV(a)).deleted() || w.status(WV(b)).deleted() || w.status(WV(c)).deleted())
            return false;
        const auto h = w.find_halfedge(WV(a), WV(b));
        if (!h.is_valid())
            return false;
        const auto f = w.face_handle(h);
        return f.is_valid() && !w.status(f).deleted() &&
               w.to_vertex_handle(w.next_halfedge_handle(h)) == WV(c);
    }

    // The user's mesh has a face with these corners, in this order.
    bool user_has_face(VertexHandle a, VertexHandle b, VertexHandle c) const {
        const auto h = mesh_.find_halfedge(a, b);
        return h.is_valid() && mesh_.face_handle(h).is_valid() &&
               mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h)) == c;
    }

    // Makes the user's mesh show the library's. A triangle OpenMesh refuses (it never did on the
    // meshes we test; it would take a vertex OpenMesh cannot join two fans at) is not left as a
    // hole: the erases whose ring holds it are undone in the library and the write-back runs again,
    // so those nodes stay and their fans come back. Each round brings nodes back, so it ends.
    void write_back() {
        for (;;) {
            const std::vector<std::array<VertexHandle, 3>> refused = write_back_once();
            failed_faces_ = refused.size();
            if (refused.empty() || !undo_erases_under(refused))
                return;
        }
    }

    // Faces gone are deleted, erased vertices marked deleted (recovered ones live again), new
    // triangles added, those next to a present face first (so OpenMesh need not join separate fans
    // at a vertex where that can be helped). Returns the triangles OpenMesh refused.
    std::vector<std::array<VertexHandle, 3>> write_back_once() {
        for (auto fh : mesh_.faces()) {
            std::array<int, 3> w{};
            int i = 0;
            for (auto vh : mesh_.fv_range(fh))
                if (i < 3)
                    w[std::size_t(i++)] = work_vertex_[std::size_t(vh.idx())];
            if (w[0] >= 0 && w[1] >= 0 && w[2] >= 0 && !work_has_face(w[0], w[1], w[2]))
                mesh_.delete_face(fh, false);
        }
        for (std::size_t i = 0; i < user_vertex_.size(); ++i) {
            const bool erased = work_->status(tinlod::Mesh::VertexHandle(int(i))).deleted();
            mesh_.status(user_vertex_[i]).set_deleted(erased);
        }
        std::vector<std::array<VertexHandle, 3>> pending, refused;
        for (auto fh : work_->faces()) {
            std::array<VertexHandle, 3> u;
            int i = 0;
            for (auto vh : work_->fv_range(fh))
                u[std::size_t(i++)] = user_vertex_[std::size_t(vh.idx())];
            if (!user_has_face(u[0], u[1], u[2]))
                pending.push_back(u);
        }
        while (!pending.empty()) {
            // A pass adds the faces that share an edge with the mesh; when none does, the first
            // one goes anyway. Each pass adds a face or gives one up.
            std::size_t kept = 0;
            bool added = false;
            for (const auto &u : pending) {
                if (touches_mesh(u) && mesh_.add_face(u[0], u[1], u[2]).is_valid())
                    added = true;
                else
                    pending[kept++] = u; // maybe once its neighbours are in
            }
            pending.resize(kept);
            if (!added && !pending.empty()) {
                const auto u = pending.front();
                pending.erase(pending.begin());
                if (!mesh_.add_face(u[0], u[1], u[2]).is_valid())
                    refused.push_back(u);
            }
        }
        return refused;
    }

    // Undoes, in the library, every erase whose ring holds all corners of a refused triangle (the
    // one that made it among them). False when there is none.
    bool undo_erases_under(const std::vector<std::array<VertexHandle, 3>> &refused) {
        std::vector<tinlod::Mesh::VertexHandle> undo;
        for (std::size_t i = 0; i < user_vertex_.size(); ++i) {
            const tinlod::Mesh::VertexHandle x{int(i)};
            if (!eraser_->is_erased(x))
                continue;
            const tinlod::ErasedNodeRing ring = eraser_->ring(x);
            auto holds = [&](VertexHandle u) {
                const auto w = std::uint32_t(work_vertex_[std::size_t(u.idx())]);
                return std::find(ring.nodes.begin(), ring.nodes.end(), w) != ring.nodes.end();
            };
            for (const auto &t : refused)
                if (holds(t[0]) && holds(t[1]) && holds(t[2])) {
                    undo.push_back(x);
                    break;
                }
        }
        std::int64_t recovered = 0;
        for (auto x : undo)
            recovered += eraser_->recover(x);
        return recovered > 0;
    }

    // One of the face's sides is already a boundary half-edge of the user's mesh.
    bool touches_mesh(const std::array<VertexHandle, 3> &u) const {
        for (int i = 0; i < 3; ++i) {
            const auto h = mesh_.find_halfedge(u[std::size_t(i)], u[std::size_t((i + 1) % 3)]);
            if (h.is_valid() && mesh_.is_boundary(h))
                return true;
        }
        return false;
    }

    MeshT &mesh_;
    std::optional<tinlod::View> view_;
    tinlod::SpModel model_ = tinlod::SpModel::screen;
    tinlod::SignificanceOptions significance_;
    tinlod::EraseOptions options_;
    tinlod::EraseStats stats_;
    std::size_t failed_faces_ = 0;
    std::unique_ptr<tinlod::Mesh> work_;         // the library's copy the eraser edits
    std::unique_ptr<tinlod::NodeEraser> eraser_; // the erase history; goes before work_
    std::vector<VertexHandle> user_vertex_;      // the user's vertex of each library vertex
    std::vector<int> work_vertex_;               // the library vertex of each user vertex, or -1
};

} // namespace tinlod::om
