// tinlod::om::ModDistanceDecayT: the paper's distance decay as a module of OpenMesh's own
// decimation framework (DecimaterT, McDecimaterT, MixedDecimaterT), with the screen-space bound
// kept over every removed vertex as OpenMesh's ModHausdorffT keeps its world-space one.
//
// The bound. Every point a collapse v0 -> v1 removes (p0, and the points already attached to v0's
// faces) is attached to the nearest of the faces that cover v0's fan afterwards (v0's faces less
// the two the collapse removes, with v0 moved onto v1). A collapse is legal only when every such
// point stays within tolerance of those faces in screen pixels:
//
//   distance(point, surface) * screen_weight(point)    (k / OD * peripheral(OA), screen_weight.hpp)
//
// so the output holds every input vertex within tolerance pixels of its surface inside the view
// frustum, relaxed by 1 / peripheral outside it (docs/method.md). A collapse changes the corners and
// the points of v0's faces alone, whose corners are v0's one-ring, the vertices DecimaterT
// re-scores after it: no stale priority can let a later collapse break the bound.
//
// Priority: non-binary (the default) orders by the SP of the vertex the collapse removes,
//   SP = delta * k / OD * peripheral(OA), delta = distance from p0 to the faces that cover it;
// binary (set_binary(true)) is a veto beside a priority module such as ModQuadricT. Both keep the
// bound. Composes with ModNormalFlippingT and ModAspectRatioT like any stock module.
//
// The module owns one face property (the attached points) for exactly its lifetime. A removed
// point keeps the weight of the view set when it went: set the view before initialize().
#pragma once

#include "tinlod/closest_point.hpp"
#include "tinlod/screen_weight.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/view.hpp"

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace tinlod::om {

template <class MeshT> class ModDistanceDecayT : public OpenMesh::Decimater::ModBaseT<MeshT> {
  public:
    DECIMATING_MODULE(ModDistanceDecayT, MeshT, DistanceDecay);

    explicit ModDistanceDecayT(MeshT &mesh) : Base(mesh, false) {
        mesh.add_property(attached_, "tinlod:distance_decay:attached");
    }
    ~ModDistanceDecayT() override { Base::mesh().remove_property(attached_); }
    ModDistanceDecayT(const ModDistanceDecayT &) = delete;
    ModDistanceDecayT &operator=(const ModDistanceDecayT &) = delete;

    // The observer; without one every collapse is illegal.
    void set_view(const tinlod::View &view) {
        view_ = view;
        has_view_ = true;
        weigher_ = tinlod::Weigher(view_, options_);
    }
    // tau, pixels: a collapse that leaves a removed point farther than this is illegal.
    void set_tolerance(double px) { tolerance_ = px; }
    double tolerance() const { return tolerance_; }
    // Peripheral-factor parameters (the model is always screen).
    void set_significance(const tinlod::SignificanceOptions &options) {
        options_ = options;
        if (has_view_)
            weigher_ = tinlod::Weigher(view_, options_);
    }

    // A fresh start: no face holds a removed point.
    void initialize() override {
        Mesh &m = Base::mesh();
        for (auto fh : m.faces())
            m.property(attached_, fh).clear();
    }

    float collapse_priority(const CollapseInfo &ci) override {
        if (!within_bound(ci))
            return float(Base::ILLEGAL_COLLAPSE);
        return Base::is_binary() ? float(Base::LEGAL_COLLAPSE) : float(significance(ci));
    }

    // Takes the points of v0's faces (the two that go included) before the collapse.
    void preprocess_collapse(const CollapseInfo &ci) override {
        gather(ci, covering_, moving_, true);
    }

    // Attaches each taken point to the nearest face that now covers v0's fan.
    void postprocess_collapse(const CollapseInfo &) override {
        Mesh &m = Base::mesh();
        for (const Attached &a : moving_) {
            typename Mesh::FaceHandle best;
            double best_d = INFINITY;
            for (auto fh : covering_) {
                const double d = face_distance(a.p, fh, typename Mesh::VertexHandle(), {});
                if (d < best_d) {
                    best_d = d;
                    best = fh;
                }
            }
            if (best.is_valid())
                m.property(attached_, best).push_back(a);
        }
    }

    // Scales the tolerance for MixedDecimaterT, as the stock modules do.
    void set_error_tolerance_factor(double factor) override {
        if (factor >= 0.0 && factor <= 1.0) {
            tolerance_ *= factor / this->error_tolerance_factor_;
            this->error_tolerance_factor_ = factor;
        }
    }

    // Whether every point the collapse removes stays within the tolerance (pixels) of a face that
    // would cover it; false without a view or when no face would.
    bool within_bound(const CollapseInfo &ci) {
        if (!has_view_ || !gather(ci, faces_, points_, false))
            return false;
        const glm::dvec3 p1 = to_glm(ci.p1);
        for (const Attached &a : points_) {
            bool covered = false;
            for (auto fh : faces_)
                if (face_distance(a.p, fh, ci.v0, p1) * a.weight <= tolerance_) {
                    covered = true;
                    break;
                }
            if (!covered)
                return false;
        }
        return true;
    }

    // SP of removing v0 by the collapse: see the file comment (+inf without a view).
    double significance(const CollapseInfo &ci) {
        if (!has_view_)
            return INFINITY;
        Mesh &m = Base::mesh();
        const glm::dvec3 p0 = to_glm(ci.p0), p1 = to_glm(ci.p1);
        double delta = INFINITY;
        std::size_t n = 0;
        for (auto fh : m.vf_range(ci.v0))
            if (fh != ci.fl && fh != ci.fr && ++n <= k_max_fan)
                delta = std::min(delta, face_distance(p0, fh, ci.v0, p1));
        if (!std::isfinite(delta))
            delta = glm::length(p1 - p0); // every face touches v1: the move itself
        return delta * weigher_(p0);
    }

  private:
    struct Attached {
        glm::dvec3 p;
        double weight; // screen_weight at p, pixels per world unit
    };

    // Faces a circulation visits at most: no manifold mesh has such a fan, so one that does is a
    // broken one and is cut there rather than followed for ever.
    static constexpr std::size_t k_max_fan = 4096;

    // v0's faces that stay (less fl and fr) into `covering`, and the points attached to all of
    // v0's faces into `points` (taken off them when `take`), p0's last. False when the fan passes
    // k_max_fan faces.
    bool gather(const CollapseInfo &ci, std::vector<typename Mesh::FaceHandle> &covering,
                std::vector<Attached> &points, bool take) {
        Mesh &m = Base::mesh();
        covering.clear();
        points.clear();
        std::size_t n = 0;
        for (auto fh : m.vf_range(ci.v0)) {
            if (++n > k_max_fan)
                return false;
            auto &attached = m.property(attached_, fh);
            points.insert(points.end(), attached.begin(), attached.end());
            if (take)
                attached.clear();
            if (fh != ci.fl && fh != ci.fr)
                covering.push_back(fh);
        }
        points.push_back(sample(ci.p0));
        return true;
    }

    template <class Point> static glm::dvec3 to_glm(const Point &p) { return {p[0], p[1], p[2]}; }

    Attached sample(const typename Mesh::Point &p) const {
        const glm::dvec3 q = to_glm(p);
        return {q, weigher_(q)};
    }

    // Distance from p to face fh, with vertex `moved` (when valid) standing at `to`.
    double face_distance(const glm::dvec3 &p, typename Mesh::FaceHandle fh,
                         typename Mesh::VertexHandle moved, const glm::dvec3 &to) {
        const Mesh &m = Base::mesh();
        glm::dvec3 c[3];
        int i = 0;
        for (auto vh : m.fv_range(fh))
            if (i < 3) // DecimaterT works on triangle meshes
                c[i++] = vh == moved ? to : to_glm(m.point(vh));
        return i == 3 ? tinlod::triangle_distance(p, c[0], c[1], c[2]) : INFINITY;
    }

    OpenMesh::FPropHandleT<std::vector<Attached>> attached_;
    tinlod::View view_;
    bool has_view_ = false;
    double tolerance_ = 1.0;
    tinlod::SignificanceOptions options_;
    tinlod::Weigher weigher_; // the screen weight of view_ under options_
    std::vector<typename Mesh::FaceHandle> faces_, covering_;
    std::vector<Attached> points_, moving_;
};

} // namespace tinlod::om
