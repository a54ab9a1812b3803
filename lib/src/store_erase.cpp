// erase_store, measure_store_error (store_erase.hpp): triangles tested against a store through its
// quad-tree, node boxes first and tile samples where a box cannot pass whole.
#include "tinlod/store_erase.hpp"

#include "tinlod/error.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/screen_weight.hpp"
#include "tinlod/util.hpp"
#include "triangle_plane.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tinlod {

namespace {

// A triangle on the store's grid in grid units (u = column, v = row), counter-clockwise: its plane
// and its box of samples.
struct GridTriangle {
    std::array<glm::dvec3, 3> t; // (column, row, height)
    double area = 0.0;           // twice the signed area, > 0
    TrianglePlane plane;
    std::uint32_t c0 = 0, c1 = 0, r0 = 0, r1 = 0;

    GridTriangle(const glm::dvec3 &a, const glm::dvec3 &b, const glm::dvec3 &c)
        : t{a, b, c}, area((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y)), plane(a, b, c) {
        c0 = std::uint32_t(std::min({a.x, b.x, c.x}));
        c1 = std::uint32_t(std::max({a.x, b.x, c.x}));
        r0 = std::uint32_t(std::min({a.y, b.y, c.y}));
        r1 = std::uint32_t(std::max({a.y, b.y, c.y}));
    }
    // Edge k's function at (u, v), >= 0 on the triangle's side (scaled by the area).
    double edge(int k, double u, double v) const {
        const glm::dvec3 &p = t[(k + 1) % 3], &q = t[(k + 2) % 3];
        return (q.x - p.x) * (v - p.y) - (q.y - p.y) * (u - p.x);
    }
    // Whether sample (u, v) is on the triangle, edges included, with measure_error's margin.
    bool covers(double u, double v) const {
        const double eps = 1e-7 * area;
        return edge(0, u, v) >= -eps && edge(1, u, v) >= -eps && edge(2, u, v) >= -eps;
    }
    // Whether the box [u0, u1] x [v0, v1] lies wholly outside one edge.
    bool misses(double u0, double u1, double v0, double v1) const {
        for (int k = 0; k < 3; ++k)
            if (edge(k, u0, v0) < 0 && edge(k, u1, v0) < 0 && edge(k, u0, v1) < 0 &&
                edge(k, u1, v1) < 0)
                return true;
        return false;
    }
};

// Visits the store's quad-tree under triangle `g` from the root: `node(dev, lo, hi)` gets a bound
// on the deviation from g's plane of the samples of a node box on the triangle, and the box in the
// local frame (x = column * dx, y = row * dy, z the node's range), and returns true when the box
// needs no closer look; `sample(dev, p)` gets each sample under g in the tiles of the boxes that
// do, and returns false to stop the walk, which then returns false.
template <class Node, class Sample>
bool walk(TileStore &store, const GridTriangle &g, const Node &node, const Sample &sample) {
    const QuadLayout &lay = store.layout();
    const GridFrame &f = store.frame();
    const int tl = store.tile_level();
    const auto visit = [&](const auto &self, int d, std::uint32_t i, std::uint32_t j) -> bool {
        const std::uint32_t u0 = std::max(lay.x.lo(d, i), g.c0),
                            u1 = std::min(lay.x.hi(d, i), g.c1),
                            v0 = std::max(lay.y.lo(d, j), g.r0),
                            v1 = std::min(lay.y.hi(d, j), g.r1);
        if (u0 > u1 || v0 > v1 || g.misses(u0, u1, v0, v1))
            return true;
        if (d + 1 < lay.levels()) { // one-cell nodes have no bound (a 2 x 2 grid's root)
            const NodeBound b = store.bound(d, i, j);
            double pmin = INFINITY, pmax = -INFINITY;
            for (const std::uint32_t u : {u0, u1})
                for (const std::uint32_t v : {v0, v1}) {
                    const double h = g.plane.height(u, v);
                    pmin = std::min(pmin, h);
                    pmax = std::max(pmax, h);
                }
            const double dev = std::max({double(b.zmax) - pmin, pmax - double(b.zmin), 0.0});
            if (node(dev, glm::dvec3(u0 * f.dx, v0 * f.dy, b.zmin),
                     glm::dvec3(u1 * f.dx, v1 * f.dy, b.zmax)))
                return true;
        }
        if (d < tl) {
            const std::uint32_t ci = lay.x.first_child(d, i), cj = lay.y.first_child(d, j);
            for (std::uint32_t a = ci;
                 a < lay.x.count(d + 1) && lay.x.lo(d + 1, a) < lay.x.hi(d, i); ++a)
                for (std::uint32_t b = cj;
                     b < lay.y.count(d + 1) && lay.y.lo(d + 1, b) < lay.y.hi(d, j); ++b)
                    if (!self(self, d + 1, a, b))
                        return false;
            return true;
        }
        const TileSamples tile = store.tile_samples(i, j);
        for (std::uint32_t v = v0; v <= v1; ++v)
            for (std::uint32_t u = u0; u <= u1; ++u) {
                if (!g.covers(u, v))
                    continue;
                const double z = tile.at(u, v);
                if (!sample(std::abs(z - g.plane.height(u, v)), glm::dvec3(u * f.dx, v * f.dy, z)))
                    return false;
            }
        return true;
    };
    // From the deepest node whose box holds the triangle's: the walk reads no bound above it.
    int d = 0;
    std::uint32_t i = 0, j = 0;
    while (d < tl) {
        const std::uint32_t a = lay.x.interval_of(d + 1, g.c0), b = lay.y.interval_of(d + 1, g.r0);
        if (lay.x.hi(d + 1, a) < g.c1 || lay.y.hi(d + 1, b) < g.r1)
            break;
        ++d;
        i = a;
        j = b;
    }
    return visit(visit, d, i, j);
}

// Whether every sample under g deviates from it by at most `limit` weighted (deviation times the
// weight at the sample). A box passes on k over its distance to the eye when it can, which bounds
// the weight without the peripheral factor's transcendental functions.
bool within(TileStore &store, const GridTriangle &g, const Weigher &weigh, const glm::dvec3 &eye,
            double k, double limit) {
    return walk(
        store, g,
        [&](double dev, const glm::dvec3 &lo, const glm::dvec3 &hi) {
            const double dist = glm::length(glm::clamp(eye, lo, hi) - eye);
            return dev * k <= limit * dist || dev * weigh.bound(lo, hi) <= limit;
        },
        [&](double dev, const glm::dvec3 &p) { return dev == 0.0 || dev * weigh(p) <= limit; });
}

// The grid corner of a vertex of a TIN on the store's samples.
glm::dvec3 grid_corner(const Mesh &mesh, OpenMesh::VPropHandleT<std::int64_t> origin,
                       Mesh::VertexHandle v, std::uint32_t width) {
    const auto id = std::uint64_t(mesh.property(origin, v));
    return {double(id % width), double(id / width), mesh.point(v)[2]};
}

// The erase's rounds of thresholds, as fractions of the tolerance: nodes whose collapse costs
// little go first, in place of a cost order (a queue of costs would need each node's cost, a full
// walk of its ring, where a threshold's test stops at the first sample over it).
constexpr std::array<double, 4> k_rounds = {0.125, 0.25, 0.5, 1.0};
constexpr int k_last_rounds = 4; // at most this many rounds at the tolerance itself

class StoreEraser {
  public:
    StoreEraser(TileStore &store, Mesh &mesh, const Significance &model)
        : store_(store), mesh_(mesh), weigh_(model), eye_(model.view()->eye), k_(model.view()->k()),
          origin_(get_origin_property(mesh)), width_(std::uint32_t(store.frame().width)),
          dx_(store.frame().dx), dy_(store.frame().dy) {
        const std::uint64_t w = width_, h = std::uint64_t(store.frame().height);
        for (const Mesh::VertexHandle v : mesh_.vertices()) {
            const auto id = std::uint64_t(mesh_.property(origin_, v));
            const std::uint64_t c = id % w, r = id / w;
            if ((c == 0 || c == w - 1) && (r == 0 || r == h - 1))
                corners_.push_back(v);
        }
    }

    // One round over the live nodes at `limit`; the number erased.
    std::int64_t round(double limit) {
        std::int64_t erased = 0;
        for (const Mesh::VertexHandle v : mesh_.vertices())
            if (!mesh_.status(v).deleted() &&
                std::find(corners_.begin(), corners_.end(), v) == corners_.end() &&
                try_erase(v, limit))
                ++erased;
        return erased;
    }

    std::int64_t evaluations = 0;

  private:
    // Collapses v into the first neighbour whose new triangles keep their orientation and every
    // sample under them within limit; a node on the border only along it (the border is straight
    // between the grid's corners, so it keeps its shape).
    bool try_erase(Mesh::VertexHandle v, double limit) {
        const bool border = mesh_.is_boundary(v);
        for (const Mesh::HalfedgeHandle h : mesh_.voh_range(v)) {
            if (border && !mesh_.is_boundary(mesh_.edge_handle(h)))
                continue;
            ++evaluations;
            // The topology last: OpenMesh's test costs more than most failing geometric ones.
            const Mesh::VertexHandle u = mesh_.to_vertex_handle(h);
            if (collapse_keeps_bound(v, u, limit) && mesh_.is_collapse_ok(h)) {
                mesh_.collapse(h);
                return true;
            }
        }
        return false;
    }

    // Whether the fan around v with u in v's place is counter-clockwise and within limit.
    bool collapse_keeps_bound(Mesh::VertexHandle v, Mesh::VertexHandle u, double limit) {
        const glm::dvec3 pu = grid_corner(mesh_, origin_, u, width_);
        fan_.clear();
        for (const Mesh::HalfedgeHandle h : mesh_.voh_range(v)) {
            if (mesh_.is_boundary(h))
                continue;
            const Mesh::VertexHandle a = mesh_.to_vertex_handle(h),
                                     b = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
            if (a == u || b == u)
                continue; // the collapse removes this face
            const GridTriangle g(pu, grid_corner(mesh_, origin_, a, width_),
                                 grid_corner(mesh_, origin_, b, width_));
            if (!(g.area > 0.0))
                return false;
            fan_.push_back(g);
        }
        // v is one of the samples under the fan, and its height is at hand: most collapses that
        // fail, fail there, before any tile is read.
        const glm::dvec3 pv = grid_corner(mesh_, origin_, v, width_);
        const glm::dvec3 world(pv.x * dx_, pv.y * dy_, pv.z);
        for (const GridTriangle &g : fan_)
            if (g.covers(pv.x, pv.y)) {
                const double dev = std::abs(pv.z - g.plane.height(pv.x, pv.y));
                if (dev > 0.0 && !(dev * weigh_(world) <= limit))
                    return false;
                break;
            }
        for (const GridTriangle &g : fan_)
            if (!within(store_, g, weigh_, eye_, k_, limit))
                return false;
        return true;
    }

    TileStore &store_;
    Mesh &mesh_;
    Weigher weigh_;
    glm::dvec3 eye_;
    double k_;
    OpenMesh::VPropHandleT<std::int64_t> origin_;
    std::uint32_t width_;
    double dx_, dy_;
    std::vector<Mesh::VertexHandle> corners_;
    std::vector<GridTriangle> fan_;
};

} // namespace

Mesh erase_store(TileStore &store, const Significance &model, double tolerance,
                 double retrieve_share, DemEraseStats *stats) {
    if (model.model() != SpModel::screen)
        throw Error("erase_store", "needs the screen model");
    if (!(retrieve_share > 0.0 && retrieve_share <= 1.0))
        throw Error("erase_store",
                    "retrieve_share must be in (0, 1], not " + std::to_string(retrieve_share));
    DemEraseStats out;
    Stopwatch clock;
    Mesh mesh;
    {
        QuadTreeLod lod(store);
        RetrieveOptions ro;
        ro.peripheral = &model.options();
        ro.tolerance = tolerance * retrieve_share;
        const Retrieval &r = lod.retrieve(*model.view(), ro);
        out.first_stage = FirstStage::quadtree;
        out.retrieved_nodes = std::int64_t(r.nodes.size());
        out.retrieve_tol = ro.tolerance;
        mesh = to_mesh(r, store.frame());
    }
    out.retrieve_ms = clock.ms();
    clock.reset();
    out.erase.input_nodes = std::int64_t(mesh.n_vertices());
    out.erase.input_triangles = std::int64_t(mesh.n_faces());
    StoreEraser eraser(store, mesh, model);
    for (const double share : k_rounds)
        out.erase.erased += eraser.round(share * tolerance);
    for (int k = 1; k < k_last_rounds; ++k) {
        const std::int64_t erased = eraser.round(tolerance);
        out.erase.erased += erased;
        if (erased == 0)
            break;
    }
    out.erase.evaluations = eraser.evaluations;
    Mesh tin = live_copy(mesh);
    out.erase.output_nodes = std::int64_t(tin.n_vertices());
    out.erase.output_triangles = std::int64_t(tin.n_faces());
    out.erase.erase_ms = clock.ms();
    if (stats)
        *stats = out;
    return tin;
}

TinError measure_store_error(TileStore &store, const Mesh &tin, const ErrorOptions &options) {
    TinError e;
    const std::optional<View> &view = options.model.view();
    const double k = view ? view->k() : 0.0;
    OpenMesh::VPropHandleT<std::int64_t> origin;
    if (!tin.get_property_handle(origin, k_origin_property))
        throw Error("measure_store_error", "the TIN has no sample ids");
    const auto width = std::uint32_t(store.frame().width);
    for (const Mesh::FaceHandle f : tin.faces()) {
        std::array<glm::dvec3, 3> c;
        int n = 0;
        for (const Mesh::VertexHandle v : tin.fv_range(f))
            c[n++] = grid_corner(tin, origin, v, width);
        const GridTriangle g(c[0], c[1], c[2]);
        if (!(g.area > 0.0))
            continue; // degenerate in xy: covers no sample a neighbour does not
        walk(
            store, g,
            [&](double dev, const glm::dvec3 &lo, const glm::dvec3 &hi) {
                if (dev > e.max_vertical)
                    return false;
                if (!view)
                    return true;
                const double dist = glm::length(glm::clamp(view->eye, lo, hi) - view->eye);
                return dist > 0.0 && dev * k / dist <= e.max_screen_px;
            },
            [&](double dev, const glm::dvec3 &p) {
                e.max_vertical = std::max(e.max_vertical, dev);
                if (view && dev > 0.0 && (!options.frustum_only || view->in_frustum(p))) {
                    const double d = glm::length(p - view->eye);
                    e.max_screen_px = std::max(e.max_screen_px, d > 0.0 ? dev * k / d : INFINITY);
                }
                return true;
            });
    }
    return e;
}

void check_eye_above(TileStore &store, const glm::dvec3 &eye, const std::string &subject) {
    // grid_tin's diagonals alternate with the cell's parity: a crop whose first sample is at even
    // column and row keeps them.
    const GridFrame &f = store.frame();
    const double u = eye.x / f.dx, v = eye.y / f.dy;
    if (!(u >= 0 && v >= 0 && u <= f.width - 1 && v <= f.height - 1))
        return;
    const int c = std::min(int(u), f.width - 2), r = std::min(int(v), f.height - 2);
    Heightfield crop;
    crop.dx = f.dx;
    crop.dy = f.dy;
    const int c0 = c - c % 2, r0 = r - r % 2;
    crop.width = std::min(3, f.width - c0);
    crop.height = std::min(3, f.height - r0);
    const QuadLayout &lay = store.layout();
    const int tl = store.tile_level();
    for (int y = r0; y < r0 + crop.height; ++y)
        for (int x = c0; x < c0 + crop.width; ++x) {
            const std::uint32_t i = lay.x.interval_of(tl, std::min<std::uint32_t>(x, f.width - 2)),
                                j = lay.y.interval_of(tl, std::min<std::uint32_t>(y, f.height - 2));
            crop.z.push_back(store.tile_samples(i, j).at(x, y));
        }
    check_eye_above(crop, eye - glm::dvec3(c0 * f.dx, r0 * f.dy, 0.0), subject);
}

} // namespace tinlod
