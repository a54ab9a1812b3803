// Fuzz target: the node-erase decimater (lib/src/erase) and the refiner's engine (lib/src/refine)
// on small TINs and views. The input decodes into a grid of at most 16x16 heights, a view, an SP
// model, a tolerance and a node budget. After erase(), after an update to a second view and after
// a budget run, the TIN must be free of fold-overs, manifold, a disk with the input's outline,
// with counts that match the mesh and an error (measured over every sample) within the bound;
// recover_all() must give back the input's node coordinates and triangles exactly. A broken
// invariant aborts with a line naming it.
#include "refine/update.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/error.hpp"
#include "tinlod/metrics.hpp"

#include "fuzz_grid.hpp"

#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace {

using namespace tinlod;

void check(bool ok, const char *what) {
    if (!ok) {
        std::fprintf(stderr, "fuzz_erase: invariant broken: %s\n", what);
        std::abort();
    }
}

using Triangle = std::array<int, 3>;

// Live triangles as vertex idx triples rotated to start at the smallest (orientation kept), sorted.
std::vector<Triangle> triangle_set(const Mesh &mesh) {
    std::vector<Triangle> out;
    for (auto f : mesh.faces()) {
        Triangle t;
        int i = 0;
        for (auto v : f.vertices())
            t[i++] = v.idx();
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
}

double xy_area2(const Mesh &mesh, const Triangle &t) {
    const auto a = mesh.point(Mesh::VertexHandle(t[0]));
    const auto b = mesh.point(Mesh::VertexHandle(t[1]));
    const auto c = mesh.point(Mesh::VertexHandle(t[2]));
    return (double(b[0]) - a[0]) * (double(c[1]) - a[1]) -
           (double(c[0]) - a[0]) * (double(b[1]) - a[1]);
}

// The invariants of any state of the eraser's TIN; `input_area` is the xy area of the input.
void check_tin(const NodeEraser &eraser, double input_area) {
    const Mesh &mesh = eraser.mesh();
    std::int64_t live_nodes = 0;
    for (auto v : mesh.vertices()) {
        ++live_nodes;
        check(mesh.is_manifold(v), "a live node is not manifold");
        check(!mesh.is_isolated(v), "a live node belongs to no live face");
    }
    const std::vector<Triangle> faces = triangle_set(mesh);
    check(live_nodes == eraser.live_nodes(), "live_nodes() differs from the mesh");
    check(std::int64_t(faces.size()) == eraser.live_triangles(),
          "live_triangles() differs from the mesh");
    std::map<std::pair<int, int>, int> directed, undirected;
    double area2 = 0;
    for (const Triangle &t : faces) {
        for (int i : t)
            check(!mesh.status(Mesh::VertexHandle(i)).deleted(), "a live face uses an erased node");
        const double a2 = xy_area2(mesh, t);
        check(a2 > 0, "a live face is not counter-clockwise in xy (fold-over)");
        area2 += a2;
        for (int i = 0; i < 3; ++i) {
            const int a = t[i], b = t[(i + 1) % 3];
            check(++directed[{a, b}] == 1, "two faces share a directed edge");
            check(++undirected[{std::min(a, b), std::max(a, b)}] <= 2,
                  "an edge has more than two faces");
        }
    }
    check(live_nodes - std::int64_t(undirected.size()) + std::int64_t(faces.size()) == 1,
          "the TIN is no longer a disk (Euler characteristic)");
    check(std::abs(0.5 * area2 - input_area) <= 1e-9 * input_area, "the outline moved (xy area)");
}

// Rounding of a height difference (world units), and the same seen from `view` at the node
// nearest the eye (pixels): the slack of the bound checks, as the decimater's own measure and
// measure_error interpolate with different formulas. Infinite when the eye stands on a node.
struct Slack {
    double z = 0, px = 0;
};

Slack slack_of(const Heightfield &hf, const View &view, double max_abs_z) {
    Slack slack;
    slack.z = 1e-9 * (max_abs_z + 1);
    double nearest = std::numeric_limits<double>::infinity();
    for (int r = 0; r < hf.height; ++r)
        for (int c = 0; c < hf.width; ++c)
            nearest = std::min(
                nearest, glm::length(glm::dvec3(c * hf.dx, r * hf.dy, hf.at(c, r)) - view.eye));
    slack.px = slack.z * view.k() / nearest;
    return slack;
}

// The bound the erase claims, as the eraser measures it and over every sample of the grid.
void check_bound(const Heightfield &hf, const NodeEraser &eraser, const View &view, SpModel model,
                 double tolerance, const Slack &slack) {
    if (std::isinf(tolerance))
        return;
    const bool vertical = model == SpModel::vertical;
    const double limit = tolerance * (1 + 1e-6) + (vertical ? slack.z : slack.px);
    check(!(eraser.measure().max_weighted > limit), "the eraser measures its error > bound");
    ErrorOptions eo;
    eo.model = Significance::screen(view);
    const TinError e = measure_error(hf, eraser.mesh(), eo);
    check(e.uncovered == 0, "a sample is not covered by the TIN");
    check(!((vertical ? e.max_vertical : e.max_screen_px) > limit), "measured error > bound");
}

void check_recovered(NodeEraser &eraser, const Mesh &input,
                     const std::vector<Triangle> &input_faces) {
    eraser.recover_all();
    const Mesh &mesh = eraser.mesh();
    check(eraser.live_nodes() == std::int64_t(input.n_vertices()),
          "recover_all() left nodes erased");
    for (auto v : input.vertices())
        check(!mesh.status(v).deleted() && mesh.point(v) == input.point(v),
              "recover_all() did not restore a node exactly");
    check(triangle_set(mesh) == input_faces, "recover_all() did not restore the triangles");
}

View take_view(FuzzedDataProvider &in, double extent, double zmid) {
    auto coordinate = [&] { return in.ConsumeIntegralInRange<int>(-64, 64) * extent / 32; };
    View view;
    view.eye = {coordinate(), coordinate(), zmid + coordinate()};
    view.at = {coordinate(), coordinate(), zmid + coordinate()};
    static constexpr double k_fov[] = {60, 10, 120, 179};
    view.fov_deg = in.PickValueInArray(k_fov);
    static constexpr std::array<int, 2> k_viewport[] = {
        {1920, 1080}, {64, 64}, {1, 1}, {4000, 100}};
    const auto vp = in.PickValueInArray(k_viewport);
    view.viewport_w = vp[0];
    view.viewport_h = vp[1];
    return view;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    Heightfield hf;
    const double zscale = fuzz::take_grid(in, 16, hf);
    static constexpr SpModel k_model[] = {SpModel::screen, SpModel::paper, SpModel::vertical};
    const SpModel model = in.PickValueInArray(k_model);
    EraseOptions options;
    static constexpr double k_tolerance[] = {1, 0,  0.25,
                                             4, 64, std::numeric_limits<double>::infinity()};
    options.tolerance =
        in.PickValueInArray(k_tolerance) * (model == SpModel::vertical ? zscale : 1.0);
    options.projection = in.ConsumeBool() ? Projection::automatic : Projection::xy;
    options.erase_boundary = in.ConsumeBool();
    erase::HistoryOptions history;
    history.shallow_history = in.ConsumeBool();
    const bool compact = in.ConsumeBool(); // drop the erased edges and faces before the update
    options.max_valence = in.ConsumeIntegralInRange(3, k_max_ring);
    const std::int64_t budget = in.ConsumeIntegralInRange(1, hf.width * hf.height);

    const double extent = std::max((hf.width - 1) * hf.dx, (hf.height - 1) * hf.dy);
    const View view = take_view(in, extent, 0);
    const View next = take_view(in, extent, 0);
    try {
        validate(view);
        validate(next);
    } catch (const Error &) {
        return 0;
    }
    // Heights last: a short input leaves the rest of the grid flat, which is what erases most.
    const double max_abs_z = fuzz::take_heights(in, zscale, hf);
    const Slack slack = slack_of(hf, view, max_abs_z), next_slack = slack_of(hf, next, max_abs_z);
    const Significance sp = Significance::of(model, view, {});

    const Mesh input = grid_tin(hf);
    const std::vector<Triangle> input_faces = triangle_set(input);
    const double input_area = (hf.width - 1) * hf.dx * (hf.height - 1) * hf.dy;

    {
        Mesh work = input;
        refine::Engine engine(work, sp, options, history);
        NodeEraser &eraser = engine.eraser;
        const EraseStats stats = eraser.erase();
        check(stats.input_nodes == std::int64_t(input.n_vertices()), "stats.input_nodes");
        check(stats.output_nodes == eraser.live_nodes(), "stats.output_nodes");
        check(stats.output_triangles == eraser.live_triangles(), "stats.output_triangles");
        check(stats.erased == stats.input_nodes - stats.output_nodes, "stats.erased");
        check_tin(eraser, input_area);
        check_bound(hf, eraser, view, model, options.tolerance, slack);
        Mesh compacted;
        if (compact) {
            engine.compact();
            compacted = work;
            engine.rebind(compacted);
            check(compacted.n_faces() == std::size_t(eraser.live_triangles()),
                  "compact kept erased faces");
            check_tin(eraser, input_area);
        }
        if (model != SpModel::vertical && std::isfinite(options.tolerance)) {
            engine.update(next, options.tolerance, 0.75 * options.tolerance);
            check_tin(eraser, input_area);
            check_bound(hf, eraser, next, model, options.tolerance, next_slack);
        }
        check_recovered(eraser, input, input_faces);
    }
    {
        Mesh work = input;
        EraseOptions by_budget = options;
        by_budget.max_nodes = budget;
        NodeEraser eraser = erase::EraserAccess::make(work, sp, by_budget, history, nullptr);
        eraser.erase();
        check(eraser.live_nodes() >= budget, "the budget run erased below max_nodes");
        check_tin(eraser, input_area);
        check_bound(hf, eraser, view, model, options.tolerance, slack);
        check_recovered(eraser, input, input_faces);
    }
    return 0;
}
