// Exhaustive geometric error of a TIN against its DEM: every triangle is rasterised over the
// sample grid and the interpolated height compared with every sample it covers.
#include "tinlod/metrics.hpp"

#include "triangle_plane.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tinlod {

namespace {

// A triangle corner in grid units (u = column, v = row) with its height.
struct Corner {
    double u, v, z;
};

class ErrorAccumulator {
  public:
    ErrorAccumulator(const Heightfield &hf, const ErrorOptions &options)
        : hf_(hf), options_(options), covered_(static_cast<std::size_t>(hf.size()), 0) {
        if (options.model.view())
            k_ = options.model.view()->k();
    }

    // The corners by value: a local copy stays in registers across the byte stores to covered_,
    // which may alias a reference.
    void triangle(const std::array<Corner, 3> t) {
        const double area =
            (t[1].u - t[0].u) * (t[2].v - t[0].v) - (t[2].u - t[0].u) * (t[1].v - t[0].v);
        if (std::abs(area) < 1e-12)
            return; // degenerate in xy: covers no sample that a neighbour does not
        const double eps = 1e-7 * std::abs(area);
        const int c0 = std::max(0, int(std::ceil(std::min({t[0].u, t[1].u, t[2].u}) - 1e-6)));
        const int c1 =
            std::min(hf_.width - 1, int(std::floor(std::max({t[0].u, t[1].u, t[2].u}) + 1e-6)));
        const int r0 = std::max(0, int(std::ceil(std::min({t[0].v, t[1].v, t[2].v}) - 1e-6)));
        const int r1 =
            std::min(hf_.height - 1, int(std::floor(std::max({t[0].v, t[1].v, t[2].v}) + 1e-6)));
        // Each edge function is affine in the column on a row, w = a + b c: the columns where it
        // passes the test below lie on one side of -(a +- eps) / b. That side, a column wider for
        // rounding, bounds the row's run; the test itself decides, as over the whole box. Only on
        // a box wider than k_narrow_from columns: on a narrower one the bounds cost more than the
        // tests they save (a 1025² crop at 5 m has about two samples a triangle).
        constexpr int k_narrow_from = 8;
        const bool narrow = c1 - c0 >= k_narrow_from;
        const double s = area > 0 ? 1.0 : -1.0;
        const std::array<double, 3> b = {s * (t[1].v - t[2].v), s * (t[2].v - t[0].v),
                                         s * (t[0].v - t[1].v)};
        for (int r = r0; r <= r1; ++r) {
            const double w0_at0 = t[1].u * (t[2].v - r) - t[2].u * (t[1].v - r);
            const double w1_at0 = t[2].u * (t[0].v - r) - t[0].u * (t[2].v - r);
            const std::array<double, 3> a = {s * w0_at0, s * w1_at0, s * (area - w0_at0 - w1_at0)};
            double lo = c0, hi = c1;
            for (int k = 0; k < 3 && narrow; ++k) {
                if (std::abs(b[k]) < 1e-3)
                    continue; // nearly parallel to the row: the bound would amplify rounding
                const double edge = (-eps - a[k]) / b[k];
                if (b[k] > 0)
                    lo = std::max(lo, std::ceil(edge) - 1.0);
                else
                    hi = std::min(hi, std::floor(edge) + 1.0);
            }
            for (int c = int(lo); c <= int(hi); ++c) {
                // Barycentric weights from the three edge functions, scaled by the signed area.
                const double w0 = (t[1].u - c) * (t[2].v - r) - (t[2].u - c) * (t[1].v - r);
                const double w1 = (t[2].u - c) * (t[0].v - r) - (t[0].u - c) * (t[2].v - r);
                const double w2 = area - w0 - w1;
                const bool inside = area > 0 ? (w0 >= -eps && w1 >= -eps && w2 >= -eps)
                                             : (w0 <= eps && w1 <= eps && w2 <= eps);
                if (!inside)
                    continue;
                const std::size_t id = std::size_t(r) * hf_.width + c;
                if (covered_[id])
                    continue;
                covered_[id] = 1;
                sample(id, c, r,
                       TrianglePlane::interpolate(w0, w1, w2, t[0].z, t[1].z, t[2].z, area));
            }
        }
    }

    TinError finish() {
        result_.uncovered = std::count(covered_.begin(), covered_.end(), std::uint8_t(0));
        if (result_.samples > 0)
            result_.rms_vertical = std::sqrt(sum_sq_ / double(result_.samples));
        return result_;
    }

  private:
    void sample(std::size_t id, int c, int r, double z_tin) {
        const double zs = hf_.z[id];
        const double dz = std::abs(zs - z_tin);
        ++result_.samples;
        sum_sq_ += dz * dz;
        if (dz > result_.max_vertical) {
            result_.max_vertical = dz;
            if (!options_.model.view())
                result_.worst_sample = std::int64_t(id);
        }
        if (!options_.model.view() || dz == 0.0)
            return;
        const glm::dvec3 p(c * hf_.dx, r * hf_.dy, zs);
        if (options_.frustum_only && !options_.model.view()->in_frustum(p))
            return;
        const double d = glm::length(p - options_.model.view()->eye);
        const double px = d > 0 ? dz * k_ / d : INFINITY;
        if (px > result_.max_screen_px) {
            result_.max_screen_px = px;
            result_.worst_sample = std::int64_t(id);
        }
    }

    const Heightfield &hf_;
    const ErrorOptions &options_;
    std::vector<std::uint8_t> covered_; // a byte a sample: a bit took 8 instructions a test
    double k_ = 0.0;
    double sum_sq_ = 0.0;
    TinError result_;
};

// Mesh points are floats: a node standing on a sample comes back a few 1e-5 grid units off it.
double snap(double g) {
    const double n = std::round(g);
    return std::abs(g - n) < 1e-3 ? n : g;
}

} // namespace

TinError measure_error(const Heightfield &hf, const Mesh &tin, const ErrorOptions &options) {
    assert(hf.width >= 2 && hf.height >= 2);
    ErrorAccumulator acc(hf, options);
    // Each vertex's corner once, not once per face round it (about six).
    std::vector<Corner> corners(tin.n_vertices());
    for (std::size_t v = 0; v < corners.size(); ++v) {
        const auto &p = tin.point(Mesh::VertexHandle(int(v)));
        corners[v] = {snap(p[0] / hf.dx), snap(p[1] / hf.dy), p[2]};
    }
    for (auto f : tin.faces()) {
        // The corners in the order of f.vertices(): the face's half-edge's end, then onwards.
        const auto h0 = tin.halfedge_handle(f), h1 = tin.next_halfedge_handle(h0),
                   h2 = tin.next_halfedge_handle(h1);
        acc.triangle({corners[std::size_t(tin.to_vertex_handle(h0).idx())],
                      corners[std::size_t(tin.to_vertex_handle(h1).idx())],
                      corners[std::size_t(tin.to_vertex_handle(h2).idx())]});
    }
    return acc.finish();
}

TinError measure_error(const Heightfield &hf, const std::vector<std::uint32_t> &triangles,
                       const ErrorOptions &options) {
    assert(hf.width >= 2 && hf.height >= 2 && triangles.size() % 3 == 0);
    ErrorAccumulator acc(hf, options);
    const std::uint32_t w = static_cast<std::uint32_t>(hf.width);
    for (std::size_t i = 0; i < triangles.size(); i += 3) {
        std::array<Corner, 3> t;
        for (int j = 0; j < 3; ++j) {
            const std::uint32_t id = triangles[i + j];
            t[j] = {double(id % w), double(id / w), hf.z[id]};
        }
        acc.triangle(t);
    }
    return acc.finish();
}

} // namespace tinlod
