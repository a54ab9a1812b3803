// The focal observation point of the paper's step 1: the observation axis cast onto the surface
// through a uniform xy grid of faces, walked cell by cell along the ray (Amanatides-Woo DDA).
#include "tinlod/focal.hpp"

#include <algorithm>
#include <cmath>

namespace tinlod {

FocalIndex::FocalIndex(const Mesh &mesh) {
    corners_.reserve(mesh.n_faces() * 3);
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    double sum_z = 0.0;
    std::size_t nodes = 0;
    for (auto v : mesh.vertices()) {
        sum_z += mesh.point(v)[2];
        ++nodes;
    }
    mean_z_ = nodes ? sum_z / double(nodes) : 0.0;
    for (auto f : mesh.faces())
        for (auto v : f.vertices()) {
            const auto &p = mesh.point(v);
            corners_.emplace_back(p[0], p[1], p[2]);
            lo = glm::min(lo, glm::dvec2(p[0], p[1]));
            hi = glm::max(hi, glm::dvec2(p[0], p[1]));
        }
    const std::size_t faces = corners_.size() / 3;
    if (faces == 0)
        return;
    lo_ = lo;
    hi_ = hi;
    const glm::dvec2 extent = glm::max(hi - lo, glm::dvec2(1e-9));
    // About two faces per cell.
    cell_ = std::max(std::sqrt(extent.x * extent.y / std::max<double>(1.0, faces / 2.0)), 1e-9);
    nx_ = std::clamp(int(extent.x / cell_) + 1, 1, 1 << 14);
    ny_ = std::clamp(int(extent.y / cell_) + 1, 1, 1 << 14);
    cell_ = std::max(extent.x / (nx_ - 0.5), extent.y / (ny_ - 0.5));
    auto cell_range = [&](std::size_t f, int &c0, int &c1, int &r0, int &r1) {
        const glm::vec3 *t = &corners_[3 * f];
        const double x0 = std::min({t[0].x, t[1].x, t[2].x}),
                     x1 = std::max({t[0].x, t[1].x, t[2].x});
        const double y0 = std::min({t[0].y, t[1].y, t[2].y}),
                     y1 = std::max({t[0].y, t[1].y, t[2].y});
        c0 = std::clamp(int((x0 - lo_.x) / cell_), 0, nx_ - 1);
        c1 = std::clamp(int((x1 - lo_.x) / cell_), 0, nx_ - 1);
        r0 = std::clamp(int((y0 - lo_.y) / cell_), 0, ny_ - 1);
        r1 = std::clamp(int((y1 - lo_.y) / cell_), 0, ny_ - 1);
    };
    cell_start_.assign(std::size_t(nx_) * ny_ + 1, 0);
    for (std::size_t f = 0; f < faces; ++f) {
        int c0, c1, r0, r1;
        cell_range(f, c0, c1, r0, r1);
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c)
                ++cell_start_[std::size_t(r) * nx_ + c + 1];
    }
    for (std::size_t i = 1; i < cell_start_.size(); ++i)
        cell_start_[i] += cell_start_[i - 1];
    cell_faces_.resize(cell_start_.back());
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t f = 0; f < faces; ++f) {
        int c0, c1, r0, r1;
        cell_range(f, c0, c1, r0, r1);
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c)
                cell_faces_[fill[std::size_t(r) * nx_ + c]++] = std::uint32_t(f);
    }
}

// Ray parameter of the hit of o + t d with triangle t (Moller-Trumbore), or +inf.
static double intersect(const glm::dvec3 &o, const glm::dvec3 &d, const glm::vec3 *t) {
    const glm::dvec3 a(t[0]), e1 = glm::dvec3(t[1]) - a, e2 = glm::dvec3(t[2]) - a;
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-300)
        return INFINITY;
    const glm::dvec3 s = o - a;
    const double u = glm::dot(s, p) / det;
    if (u < -1e-12 || u > 1.0 + 1e-12)
        return INFINITY;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) / det;
    if (v < -1e-12 || u + v > 1.0 + 1e-12)
        return INFINITY;
    const double t_hit = glm::dot(e2, q) / det;
    return t_hit > 0.0 ? t_hit : INFINITY;
}

FocalPoint FocalIndex::cast(const View &view) const {
    const glm::dvec3 o = view.eye, d = view.axis();
    FocalPoint result;
    if (!cell_faces_.empty()) {
        // Clip the ray's xy projection to the grid's box, then step cell by cell.
        double t0 = 0.0, t1 = INFINITY;
        const double box_lo[2] = {lo_.x, lo_.y};
        const double box_hi[2] = {lo_.x + nx_ * cell_, lo_.y + ny_ * cell_};
        bool inside = true;
        for (int k = 0; k < 2 && inside; ++k) {
            if (std::abs(d[k]) < 1e-15) {
                inside = o[k] >= box_lo[k] && o[k] <= box_hi[k];
                continue;
            }
            double ta = (box_lo[k] - o[k]) / d[k], tb = (box_hi[k] - o[k]) / d[k];
            if (ta > tb)
                std::swap(ta, tb);
            t0 = std::max(t0, ta);
            t1 = std::min(t1, tb);
        }
        if (inside && t0 <= t1) {
            const glm::dvec3 start = o + t0 * d;
            int c = std::clamp(int((start.x - lo_.x) / cell_), 0, nx_ - 1);
            int r = std::clamp(int((start.y - lo_.y) / cell_), 0, ny_ - 1);
            const int step_c = d.x > 0 ? 1 : -1, step_r = d.y > 0 ? 1 : -1;
            const double dt_c = std::abs(d.x) > 1e-15 ? cell_ / std::abs(d.x) : INFINITY;
            const double dt_r = std::abs(d.y) > 1e-15 ? cell_ / std::abs(d.y) : INFINITY;
            double next_c = std::abs(d.x) > 1e-15
                                ? (lo_.x + (c + (step_c > 0 ? 1 : 0)) * cell_ - o.x) / d.x
                                : INFINITY;
            double next_r = std::abs(d.y) > 1e-15
                                ? (lo_.y + (r + (step_r > 0 ? 1 : 0)) * cell_ - o.y) / d.y
                                : INFINITY;
            double best = INFINITY;
            for (;;) {
                const std::size_t cell = std::size_t(r) * nx_ + c;
                for (std::uint32_t i = cell_start_[cell]; i < cell_start_[cell + 1]; ++i)
                    best = std::min(best, intersect(o, d, &corners_[3 * cell_faces_[i]]));
                const double cell_exit = std::min(next_c, next_r);
                if (best <= cell_exit)
                    break; // the nearest hit lies in a cell already walked
                if (next_c < next_r) {
                    c += step_c;
                    next_c += dt_c;
                } else {
                    r += step_r;
                    next_r += dt_r;
                }
                if (c < 0 || c >= nx_ || r < 0 || r >= ny_)
                    break; // left the grid
            }
            if (std::isfinite(best)) {
                result.point = o + best * d;
                result.distance = best;
                result.hit = true;
                return result;
            }
        }
    }
    // Missed: the axis against the mean-height plane, else the look-at point.
    if (std::abs(d.z) > 1e-12) {
        const double t = (mean_z_ - o.z) / d.z;
        if (t > 0.0) {
            result.point = o + t * d;
            result.distance = t;
            return result;
        }
    }
    result.point = view.at;
    result.distance = glm::length(view.at - view.eye);
    return result;
}

FocalPoint focal_point(const Mesh &mesh, const View &view) { return FocalIndex(mesh).cast(view); }

} // namespace tinlod
