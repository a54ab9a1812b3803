// Sampled symmetric Hausdorff distance between triangle meshes (hausdorff.hpp), after Cignon,
// Rocchini and Scopigno, "Metro: measuring error on simplified surfaces" (1998): area-weighted
// samples on one surface, exact point-to-surface distance to the other. The nearest triangle is
// found in a bounding-volume hierarchy (median split on the longest axis, best-first descent);
// the point-triangle distance is Ericson's (tinlod/closest_point.hpp).
#include "tinlod/hausdorff.hpp"
#include "tinlod/closest_point.hpp"
#include "tinlod/error.hpp"
#include "tinlod/util.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <thread>

namespace tinlod {

namespace {

struct Triangle {
    glm::dvec3 a, b, c;
};

std::vector<Triangle> live_triangles(const Mesh &mesh) {
    std::vector<Triangle> out;
    out.reserve(mesh.n_faces());
    for (auto f : mesh.faces()) {
        if (mesh.status(f).deleted())
            continue;
        const auto p = face_corners(mesh, f);
        out.push_back({p[0], p[1], p[2]});
    }
    return out;
}

double squared(const glm::dvec3 &v) { return glm::dot(v, v); }

class TriangleBvh {
  public:
    explicit TriangleBvh(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {
        nodes_.reserve(2 * triangles_.size() / k_leaf_size + 1);
        build(0, triangles_.size());
    }

    // Squared distance from p to the nearest point of any triangle.
    double squared_distance(const glm::dvec3 &p) const {
        double best = std::numeric_limits<double>::infinity();
        std::size_t stack[128];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node &node = nodes_[stack[--top]];
            if (box_distance(node, p) >= best)
                continue;
            if (node.count > 0) {
                for (std::size_t i = node.first; i < node.first + node.count; ++i) {
                    const Triangle &t = triangles_[i];
                    best = std::min(best, squared(p - closest_on_triangle(p, t.a, t.b, t.c)));
                }
                continue;
            }
            const std::size_t near = node.first, far = node.right;
            const double dn = box_distance(nodes_[near], p), df = box_distance(nodes_[far], p);
            // Push the farther child first so the nearer is searched first and tightens `best`.
            if (dn <= df) {
                stack[top++] = far;
                stack[top++] = near;
            } else {
                stack[top++] = near;
                stack[top++] = far;
            }
        }
        return best;
    }

  private:
    static constexpr std::size_t k_leaf_size = 4;

    struct Node {
        glm::dvec3 lo, hi;
        std::size_t first = 0; // leaf: first triangle; inner: left child (the next node)
        std::size_t count = 0; // leaf: triangles; inner: 0
        std::size_t right = 0; // inner: right child
    };

    static double box_distance(const Node &node, const glm::dvec3 &p) {
        return squared(p - glm::clamp(p, node.lo, node.hi));
    }

    // Builds the node over triangles_[begin, end) and returns its index. Recursion depth is
    // log2 of the triangle count, as every split halves the range.
    std::size_t build(std::size_t begin, std::size_t end) {
        const std::size_t index = nodes_.size();
        nodes_.emplace_back();
        glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
        glm::dvec3 clo = lo, chi = hi;
        for (std::size_t i = begin; i < end; ++i) {
            const Triangle &t = triangles_[i];
            lo = glm::min(lo, glm::min(t.a, glm::min(t.b, t.c)));
            hi = glm::max(hi, glm::max(t.a, glm::max(t.b, t.c)));
            const glm::dvec3 centre = (t.a + t.b + t.c) / 3.0;
            clo = glm::min(clo, centre);
            chi = glm::max(chi, centre);
        }
        nodes_[index].lo = lo;
        nodes_[index].hi = hi;
        if (end - begin <= k_leaf_size) {
            nodes_[index].first = begin;
            nodes_[index].count = end - begin;
            return index;
        }
        const glm::dvec3 extent = chi - clo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        const std::size_t mid = begin + (end - begin) / 2;
        std::nth_element(
            triangles_.begin() + std::ptrdiff_t(begin), triangles_.begin() + std::ptrdiff_t(mid),
            triangles_.begin() + std::ptrdiff_t(end), [axis](const Triangle &s, const Triangle &t) {
                return s.a[axis] + s.b[axis] + s.c[axis] < t.a[axis] + t.b[axis] + t.c[axis];
            });
        const std::size_t left = build(begin, mid);
        const std::size_t right = build(mid, end);
        nodes_[index].first = left;
        nodes_[index].right = right;
        return index;
    }

    std::vector<Triangle> triangles_;
    std::vector<Node> nodes_;
};

// Every vertex used by a live face, then `count` points spread over the faces by area.
std::vector<glm::dvec3> sample_surface(const Mesh &mesh, const std::vector<Triangle> &triangles,
                                       std::int64_t count, std::uint64_t seed) {
    std::vector<glm::dvec3> points;
    points.reserve(mesh.n_vertices() + std::size_t(std::max<std::int64_t>(count, 0)));
    for (auto v : mesh.vertices()) {
        bool used = false;
        for (auto f : v.faces())
            used = used || !mesh.status(f).deleted();
        if (used) {
            const auto &q = mesh.point(v);
            points.emplace_back(q[0], q[1], q[2]);
        }
    }
    std::vector<double> cumulative(triangles.size());
    double total = 0.0;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const Triangle &t = triangles[i];
        total += 0.5 * glm::length(glm::cross(t.b - t.a, t.c - t.a));
        cumulative[i] = total;
    }
    if (!(total > 0.0))
        return points;
    // Uniform doubles from the raw 64-bit engine, so the points are the same on every platform.
    std::mt19937_64 engine(seed);
    auto uniform = [&engine] { return double(engine() >> 11) * 0x1.0p-53; };
    for (std::int64_t i = 0; i < count; ++i) {
        const double pick = uniform() * total;
        const std::size_t f = std::min<std::size_t>(
            std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), pick) -
                        cumulative.begin()),
            triangles.size() - 1);
        const double s = std::sqrt(uniform()), r = uniform();
        const Triangle &t = triangles[f];
        points.push_back((1.0 - s) * t.a + s * (1.0 - r) * t.b + s * r * t.c);
    }
    return points;
}

// Distance from each point to the surface, over max_threads() threads.
std::vector<double> distances(const std::vector<glm::dvec3> &points, const TriangleBvh &bvh) {
    std::vector<double> out(points.size());
    const std::size_t threads = std::size_t(max_threads());
    const std::size_t chunk = (points.size() + threads - 1) / threads;
    std::vector<std::thread> workers;
    for (std::size_t t = 0; t < threads; ++t)
        workers.emplace_back([&, t] {
            for (std::size_t i = t * chunk; i < std::min(points.size(), (t + 1) * chunk); ++i)
                out[i] = std::sqrt(bvh.squared_distance(points[i]));
        });
    for (auto &w : workers)
        w.join();
    return out;
}

struct OneWay {
    double max = 0.0, sum = 0.0, sum_squares = 0.0, max_screen_px = 0.0;
    std::size_t count = 0;
};

OneWay one_way(const std::vector<glm::dvec3> &points, const TriangleBvh &target,
               const std::optional<View> &view) {
    OneWay r;
    const std::vector<double> d = distances(points, target);
    for (std::size_t i = 0; i < d.size(); ++i) {
        r.max = std::max(r.max, d[i]);
        r.sum += d[i];
        r.sum_squares += d[i] * d[i];
        if (view && view->in_frustum(points[i]))
            r.max_screen_px = std::max(r.max_screen_px, view->screen_px(d[i], points[i]));
    }
    r.count = points.size();
    return r;
}

} // namespace

HausdorffResult hausdorff(const Mesh &a, const Mesh &b, const HausdorffOptions &options) {
    std::vector<Triangle> ta = live_triangles(a), tb = live_triangles(b);
    if (ta.empty() || tb.empty())
        throw Error("hausdorff", "a mesh has no faces");
    const std::vector<glm::dvec3> pa = sample_surface(a, ta, options.samples, options.seed);
    const std::vector<glm::dvec3> pb = sample_surface(b, tb, options.samples, options.seed + 1);
    const OneWay ab = one_way(pa, TriangleBvh(std::move(tb)), options.model.view());
    const OneWay ba = one_way(pb, TriangleBvh(std::move(ta)), options.model.view());
    HausdorffResult r;
    r.max_a_to_b = ab.max;
    r.max_b_to_a = ba.max;
    r.max = std::max(ab.max, ba.max);
    r.max_screen_px_a_to_b = ab.max_screen_px;
    r.max_screen_px_b_to_a = ba.max_screen_px;
    r.max_screen_px = std::max(ab.max_screen_px, ba.max_screen_px);
    r.mean_a_to_b = ab.count ? ab.sum / double(ab.count) : 0.0;
    r.mean_b_to_a = ba.count ? ba.sum / double(ba.count) : 0.0;
    r.samples = std::int64_t(ab.count + ba.count);
    r.mean = r.samples ? (ab.sum + ba.sum) / double(r.samples) : 0.0;
    r.rms = r.samples ? std::sqrt((ab.sum_squares + ba.sum_squares) / double(r.samples)) : 0.0;
    return r;
}

} // namespace tinlod
