// The NodeEraser facade (decimate.hpp): the constructor that reads the input, the view, erase(),
// measure() and erase_cost(), and the one-off erase_nodes().
#include "tinlod/decimate.hpp"

#include "erase/edits.hpp"
#include "erase/erase_cost.hpp"
#include "erase/history.hpp"
#include "erase/lattice_scan.hpp"
#include "erase/state.hpp"
#include "erase/swallowed.hpp"
#include "erase/sweep.hpp"
#include "tinlod/error.hpp"
#include "tinlod/focal.hpp"
#include "tinlod/util.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tinlod {

using namespace erase;

namespace {

// The vertices marked deleted (samples a grid TIN left out); throws for one that still has edges.
std::int64_t deleted_vertices(const Mesh &m) {
    std::int64_t deleted = 0;
    for (auto v : m.all_vertices())
        if (m.status(v).deleted()) {
            if (m.halfedge_handle(v).is_valid())
                throw std::invalid_argument("NodeEraser: a deleted vertex still has edges");
            ++deleted;
        }
    return deleted;
}

// Node ids: the mesh's vertices, or a sparse lattice's samples (EraseOptions::lattice), whose
// columns' x and rows' y it reads, checking that each vertex is the sample its origin property
// names. Returns each sample's vertex (-1: none; empty without a lattice) and sets `absent` to
// the samples without one.
std::vector<std::int32_t> bind_nodes(EraserState &s, const Heightfield *lattice,
                                     std::int64_t &absent) {
    s.input.nodes = std::uint32_t(s.input.mesh->n_vertices());
    std::vector<std::int32_t> vertex_of;
    if (!lattice)
        return vertex_of;
    const Heightfield &hf = *lattice;
    if (absent > 0)
        throw std::invalid_argument("NodeEraser: a sparse lattice TIN with deleted vertices");
    s.input.origin = find_origin_property(*s.input.mesh);
    if (!s.input.origin.is_valid())
        throw std::invalid_argument("NodeEraser: a sparse lattice TIN without its samples");
    s.input.lattice = &hf;
    s.input.nodes = std::uint32_t(hf.size());
    s.input.inverse_width = 1.0 / double(hf.width);
    s.input.lattice_x.resize(std::size_t(hf.width));
    s.input.lattice_y.resize(std::size_t(hf.height));
    for (int c = 0; c < hf.width; ++c)
        s.input.lattice_x[std::size_t(c)] = grid_point(hf, c, 0)[0];
    for (int r = 0; r < hf.height; ++r)
        s.input.lattice_y[std::size_t(r)] = grid_point(hf, 0, r)[1];
    vertex_of.assign(s.input.nodes, -1);
    s.input.sample_of.resize(s.input.mesh->n_vertices());
    for (auto v : s.input.mesh->vertices()) {
        const std::int64_t x = s.input.mesh->property(s.input.origin, v);
        if (x < 0 || x >= hf.size() || vertex_of[std::size_t(x)] >= 0 ||
            s.input.mesh->point(v) != node_point(s, std::uint32_t(x)))
            throw std::invalid_argument("NodeEraser: a sparse lattice TIN's vertex is not "
                                        "its sample");
        vertex_of[std::size_t(x)] = v.idx();
        s.input.sample_of[std::size_t(v.idx())] = std::uint32_t(x);
    }
    absent = std::int64_t(s.input.nodes) - std::int64_t(s.input.mesh->n_vertices());
    return vertex_of;
}

// The projection plane (xy for a TIN: every face counter-clockwise seen from above, or as the
// options say) and whether the mesh is a grid TIN, whose faces' swallowed nodes are scanned from
// the lattice (grid_width).
void choose_projection(EraserState &s, Projection projection, std::int64_t absent) {
    bool all_ccw = true;
    for (auto f : s.input.mesh->faces()) {
        auto he = s.input.mesh->halfedge_handle(f);
        const auto &a = s.input.mesh->point(s.input.mesh->from_vertex_handle(he));
        const auto &b = s.input.mesh->point(s.input.mesh->to_vertex_handle(he));
        const auto &c = s.input.mesh->point(
            s.input.mesh->to_vertex_handle(s.input.mesh->next_halfedge_handle(he)));
        if (orient({a[0], a[1]}, {b[0], b[1]}, {c[0], c[1]}) <= 0.0) {
            all_ccw = false;
            break;
        }
    }
    s.input.xy = projection == Projection::xy || (projection == Projection::automatic && all_ccw);
    s.input.grid_w = !s.input.xy       ? 0
                     : s.input.lattice ? std::uint32_t(s.input.lattice->width)
                                       : grid_width(*s.input.mesh);
    if (s.input.lattice && s.input.grid_w == 0)
        throw std::invalid_argument("NodeEraser: a sparse lattice TIN is not counter-clockwise");
    if (absent > 0 && s.input.grid_w == 0)
        throw std::invalid_argument(
            "NodeEraser: deleted vertices in a mesh that is not a grid TIN");
}

// The per-face and per-node arrays: the face index (empty lists), the records, the live list.
void allocate(EraserState &s) {
    if (s.input.grid_w == 0) {
        s.faces.next_swallowed.assign(s.input.nodes, -1);
        s.faces.swallowed_by.assign(s.input.nodes, -1);
    }
    s.faces.face_head.assign(s.input.mesh->n_faces(), -1);
    s.faces.face_maxdev.assign(s.input.mesh->n_faces(), 0.0f);
    s.history.record_of.resize(s.input.nodes);
    s.live.list.reserve(std::size_t(s.live.count));
}

// The input's extent in xy and its area per node.
void measure_extent(EraserState &s) {
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    for (auto v : s.input.mesh->vertices()) {
        const glm::dvec3 p = to_glm(s.input.mesh->point(v));
        lo = glm::min(lo, glm::dvec2(p));
        hi = glm::max(hi, glm::dvec2(p));
    }
    if (s.input.nodes > 0) {
        const glm::dvec2 extent = hi - lo;
        s.input.area_per_node = extent.x * extent.y / double(s.input.nodes);
        s.input.lo = lo;
        s.input.hi = hi;
    }
}

// Every node with a live vertex enters the live set; the others are absent (k_absent). Takes
// bind_nodes' vertex_of, freed on return (before the absent samples' rings are made).
void build_live_set(EraserState &s, std::vector<std::int32_t> vertex_of) {
    for (std::uint32_t x = 0; x < s.input.nodes; ++x) {
        const VH v = s.input.lattice ? VH(vertex_of[x]) : VH(int(x));
        if (!v.is_valid() || s.input.mesh->status(v).deleted())
            s.history.record_of[x] = k_absent;
        else
            add_live(s, x, -1, v);
    }
}

// The option values a user can reach, checked in Release too (an assert is compiled out): each
// Error names the option at fault.
void check_options(const EraseOptions &options) {
    if (!(options.tolerance >= 0.0))
        throw Error("EraseOptions::tolerance",
                    "must be 0 or more (or +inf), not " + std::to_string(options.tolerance));
    if (options.max_nodes < 0)
        throw Error("EraseOptions::max_nodes",
                    "must be 0 (no budget) or more, not " + std::to_string(options.max_nodes));
    if (options.max_valence < 3 || options.max_valence > k_max_ring)
        throw Error("EraseOptions::max_valence", "must be in [3, " + std::to_string(k_max_ring) +
                                                     "], not " +
                                                     std::to_string(options.max_valence));
}

} // namespace

NodeEraser::NodeEraser(Mesh &mesh, const Significance &model, const EraseOptions &options)
    : NodeEraser(mesh, model, options, HistoryOptions{}, nullptr) {}

NodeEraser::NodeEraser(Mesh &mesh, const Significance &model, const EraseOptions &options,
                       const erase::HistoryOptions &history, erase::Follower *follower)
    : state_(std::make_unique<erase::EraserState>()) {
    check_options(options);
    EraserState &s = *state_;
    s.input.mesh = &mesh;
    s.input.history = history;
    s.follower = follower;
    assert(s.input.mesh->is_trimesh());
    std::int64_t absent = deleted_vertices(*s.input.mesh);
    std::vector<std::int32_t> vertex_of = bind_nodes(s, options.lattice, absent);
    s.live.count = std::int64_t(s.input.nodes) - absent;
    s.live.faces = std::int64_t(s.input.mesh->n_faces());
    choose_projection(s, options.projection, absent);
    allocate(s);
    measure_extent(s);
    if (s.follower)
        s.follower->started(s);
    build_live_set(s, std::move(vertex_of));
    s.history.absent_for_good = absent > 0 && !history.absent_history;
    if (absent > 0 && history.absent_history)
        record_absent_samples(s.input, s.live, s.history, history.retrieval_tin);
    if (absent > 0)
        swallow_absent(s);
    set_view(model, options);
}

NodeEraser::~NodeEraser() = default;
NodeEraser::NodeEraser(NodeEraser &&) noexcept = default;
NodeEraser &NodeEraser::operator=(NodeEraser &&) noexcept = default;

void NodeEraser::set_view(const Significance &model, const EraseOptions &options) {
    check_options(options);
    EraserState &s = *state_;
    s.input.options = options;
    s.weights.model = model.model();
    s.weights.significance = model.options();
    if (s.follower)
        s.follower->view_changed(); // its bounds were made under the old model

    if (const std::optional<View> &view = model.view()) {
        s.weights.view = *view;
        if (s.weights.model == SpModel::paper)
            s.weights.focal_distance = std::max(focal_point(*s.input.mesh, *view).distance, 1e-9);
    }
    classify_nodes(s);
}

namespace {

// Back to the per-vertex stamps (and keys, which the erase resets) from the live nodes, where
// compact() moved them.
void per_vertex_keys(EraserState &s) {
    if (!s.live.node_keys)
        return;
    s.live.stamp.assign(s.input.nodes, 0);
    for (std::size_t i = 0; i < s.live.list.size(); ++i)
        s.live.stamp[s.live.list[i].node] = s.live.slot_stamp[i];
    std::vector<float>().swap(s.live.slot_key);
    std::vector<std::uint8_t>().swap(s.live.slot_stamp);
    s.live.node_keys = false;
}

// The sweep (sweep.hpp) where the key is the cost (not the paper model) and a bound or a budget
// stops it, else the queue: rank every node, then pop the least.
std::int64_t erase_by_model(EraserState &s) {
    if (s.weights.model != SpModel::paper &&
        (s.input.options.max_nodes > 0 || std::isfinite(s.input.options.tolerance)))
        return sweep_erase(s);
    rank_nodes(s);
    return erase_loop(s);
}

} // namespace

EraseStats NodeEraser::erase() {
    EraserState &s = *state_;
    if (s.follower)
        s.follower->erasing();
    Stopwatch clock;
    EraseStats stats;
    stats.input_nodes = s.live.count;
    stats.input_triangles = s.live.faces;
    const std::int64_t evaluations = s.counters.evaluations;
    per_vertex_keys(s);
    stats.erased = erase_by_model(s);
    const bool shrink = s.live.list.capacity() > 2 * s.live.list.size();
    if (shrink)
        s.live.list.shrink_to_fit(); // an update keeps the live nodes only
    if (s.follower)
        s.follower->erased(shrink);
    const EraseStats now = measure();
    stats.output_nodes = s.live.count;
    stats.output_triangles = s.live.faces;
    stats.evaluations = s.counters.evaluations - evaluations;
    stats.max_weighted = now.max_weighted;
    stats.max_screen_px = now.max_screen_px;
    stats.max_vertical = now.max_vertical;
    stats.erase_ms = clock.ms();
    return stats;
}

const Mesh &NodeEraser::mesh() const { return *state_->input.mesh; }
std::int64_t NodeEraser::live_nodes() const { return state_->live.count; }
std::int64_t NodeEraser::live_triangles() const { return state_->live.faces; }

NodeEraser::Cost NodeEraser::erase_cost(Mesh::VertexHandle v) {
    EraserState &s = *state_;
    const std::uint32_t x = node_of(s, v);
    if (s.history.record_of[x] >= 0)
        throw std::invalid_argument("NodeEraser::erase_cost: the node is erased");
    Cost out;
    if (s.input.xy && s.input.area_per_node > 0.0)
        out.covered = covered_estimate(s, x);
    if (s.live.flags[x] & k_locked)
        return out;
    const std::int64_t evaluations = s.counters.evaluations;
    if (evaluate(s, v, INFINITY)) {
        out.cost = s.scratch.hole.sp;
        if (s.input.grid_w > 0)
            out.covered = std::max(out.covered, double(lattice_inside(s, s.scratch.hole)));
    }
    s.counters.evaluations = evaluations;
    return out;
}

EraseStats NodeEraser::measure() const {
    const EraserState &s = *state_;
    const Mesh &m = *s.input.mesh;
    EraseStats stats;
    stats.output_nodes = s.live.count;
    stats.output_triangles = s.live.faces;
    const bool has_view = s.weights.model != SpModel::vertical;
    const double k = has_view ? s.weights.view.k() : 0.0;
    // Each TIN face's bounds on what its swallowed nodes can show: its largest deviation, alone,
    // times the largest weight in its box and times k over the box's distance (a surface mesh's
    // faces get no bounds: each is scanned). Faces go from the largest weighted bound down, and a
    // face whose three bounds cannot raise the maxima found so far is not scanned (the erase
    // leaves most faces near the bound, so the first few settle the maxima).
    struct Bounded {
        double weighted, screen, vertical;
        FH f;
    };
    std::vector<Bounded> faces;
    faces.reserve(std::size_t(s.live.faces));
    for (auto f : m.faces()) {
        if (s.faces.face_head[f.idx()] < 0 || m.status(f).deleted())
            continue;
        const HH he = m.halfedge_handle(f);
        const glm::dvec3 a = to_glm(m.point(m.from_vertex_handle(he))),
                         b = to_glm(m.point(m.to_vertex_handle(he))),
                         c = to_glm(m.point(m.to_vertex_handle(m.next_halfedge_handle(he))));
        const double dev = 1.001 * double(s.faces.face_maxdev[f.idx()]);
        const auto [lo, hi] = swallowed_box(s.faces, s.input.xy, f, a, b, c);
        const double near =
            glm::length(glm::clamp(s.weights.view.eye, lo, hi) - s.weights.view.eye);
        faces.push_back(
            {s.input.xy ? dev * s.weights.weigher.bound(lo, hi) * k_rounded_weight : INFINITY,
             s.input.xy && has_view ? dev * k / near : INFINITY, s.input.xy ? dev : INFINITY, f});
    }
    std::sort(faces.begin(), faces.end(),
              [](const Bounded &x, const Bounded &y) { return x.weighted > y.weighted; });
    for (const Bounded &bounded : faces) {
        if (!(bounded.weighted > stats.max_weighted) && !(bounded.vertical > stats.max_vertical) &&
            (!has_view || !(bounded.screen > stats.max_screen_px)))
            continue;
        const FH f = bounded.f;
        std::int32_t u = s.faces.face_head[f.idx()];
        HH he = m.halfedge_handle(f);
        const VH va = m.from_vertex_handle(he), vb = m.to_vertex_handle(he),
                 vc = m.to_vertex_handle(m.next_halfedge_handle(he));
        const glm::dvec3 a = to_glm(m.point(va)), b = to_glm(m.point(vb)), c = to_glm(m.point(vc));
        const TrianglePlane plane = s.input.xy ? TrianglePlane(a, b, c) : TrianglePlane();
        auto add = [&](std::int32_t node) {
            const glm::dvec3 p = to_glm(node_point(s, std::uint32_t(node)));
            // The output's own error: node_deviation without the widening for float corners.
            const double dev = s.input.xy ? plane.vertical(p) : triangle_distance(p, a, b, c);
            stats.max_vertical = std::max(stats.max_vertical, dev);
            stats.max_weighted =
                std::max(stats.max_weighted, weighted(s, std::uint32_t(node), dev));
            if (has_view && s.weights.view.in_frustum(p))
                stats.max_screen_px =
                    std::max(stats.max_screen_px, dev * k / glm::length(p - s.weights.view.eye));
        };
        if (s.input.grid_w > 0)
            scan_lattice(
                s, node_of(s, va), node_of(s, vb), node_of(s, vc),
                [](const glm::dvec2 &, const glm::dvec2 &) { return 0.0; },
                [&](std::uint32_t v, const Mesh::Point &, double) {
                    add(std::int32_t(v));
                    return true;
                });
        else
            for (; u >= 0; u = s.faces.next_swallowed[u])
                add(u);
    }
    return stats;
}

EraseStats erase_nodes(Mesh &mesh, const Significance &model, const EraseOptions &options) {
    EraseStats stats;
    {
        NodeEraser eraser(mesh, model, options);
        stats = eraser.erase();
    }
    Stopwatch clock;
    mesh.garbage_collection();
    stats.erase_ms += clock.ms();
    return stats;
}

} // namespace tinlod
