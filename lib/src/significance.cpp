// The significance parameter SP = f(OD, OA, sration) of the paper's step 2, in the screen, paper
// and vertical models (formulas in significance.hpp).
#include "tinlod/significance.hpp"

#include "tinlod/focal.hpp"
#include "tinlod/screen_weight.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tinlod {

double observation_angle(const View &view, const glm::dvec3 &p) {
    const glm::dvec3 d = p - view.eye;
    const double len = glm::length(d);
    if (!(len > 0.0))
        return 0.0;
    return std::acos(std::clamp(glm::dot(d / len, view.axis()), -1.0, 1.0));
}

double peripheral_factor(const View &view, const glm::dvec3 &p,
                         const SignificanceOptions &options) {
    return Weigher(view, options).peripheral(p);
}

double screen_weight(const View &view, const glm::dvec3 &p, const SignificanceOptions &options) {
    return Weigher(view, options)(p);
}

double significance(const NodeTerms &terms, const View *view, const SignificanceOptions &options,
                    double focal_distance) {
    switch (options.model) {
    case SpModel::vertical:
        return terms.delta;
    case SpModel::screen:
        assert(view);
        return terms.od > 0.0 ? terms.delta * view->k() / terms.od * terms.peripheral : INFINITY;
    case SpModel::paper: {
        if (!(terms.od > 0.0))
            return INFINITY;
        const double angle = std::cos(std::min(terms.oa, M_PI / 2) / 2.0);
        return std::pow(std::max(terms.ration, 0.0), options.w_ration) *
               std::pow(focal_distance / terms.od, options.w_distance) *
               std::pow(angle, options.w_angle);
    }
    }
    return 0.0;
}

std::vector<float> node_weights(const Mesh &mesh, const View *view,
                                const SignificanceOptions &options) {
    std::vector<float> weight(mesh.n_vertices(), 1.0f);
    if (!view || options.model == SpModel::vertical)
        return weight;
    const Weigher weigher(*view, options);
    for (auto v : mesh.all_vertices()) { // erased nodes too: the bound weighs what faces swallowed
        const auto &p = mesh.point(v);
        weight[v.idx()] = float(weigher(glm::dvec3(p[0], p[1], p[2])));
    }
    return weight;
}

std::vector<float> node_significance(const Mesh &mesh, const View *view,
                                     const SignificanceOptions &options) {
    assert(view || options.model == SpModel::vertical);
    std::vector<float> sp(mesh.n_vertices(), 0.0f);
    const Weigher weigher(view ? *view : View{}, options);
    const double focal_distance =
        view && options.model == SpModel::paper ? focal_point(mesh, *view).distance : 1.0;
    for (auto v : mesh.vertices()) {
        if (mesh.is_boundary(v) || !mesh.halfedge_handle(v).is_valid()) {
            sp[v.idx()] = INFINITY;
            continue;
        }
        const auto &pv = mesh.point(v);
        const glm::dvec3 c(pv[0], pv[1], pv[2]);
        // The plane of the ring: through its centroid, normal to the area-weighted fan normal.
        glm::dvec3 centroid(0.0), normal(0.0);
        double length = 0.0;
        int n = 0;
        glm::dvec3 first(0.0), prev(0.0);
        for (auto u : mesh.vv_ccw_range(v)) {
            const auto &pu = mesh.point(u);
            const glm::dvec3 q(pu[0], pu[1], pu[2]);
            if (n == 0)
                first = q;
            else
                normal += glm::cross(prev - c, q - c);
            prev = q;
            centroid += q;
            length += glm::length(q - c);
            ++n;
        }
        normal += glm::cross(prev - c, first - c);
        centroid /= double(n);
        const double len = glm::length(normal);
        NodeTerms terms;
        terms.delta = len > 0.0 ? std::abs(glm::dot(c - centroid, normal / len)) : 0.0;
        terms.ration = length > 0.0 ? terms.delta / (length / n) : 0.0;
        if (view) {
            terms.od = glm::length(c - view->eye);
            terms.oa = observation_angle(*view, c);
            terms.peripheral = weigher.peripheral(c);
        }
        sp[v.idx()] = float(significance(terms, view, options, focal_distance));
    }
    return sp;
}

} // namespace tinlod
