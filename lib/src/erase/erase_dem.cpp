// erase_dem (decimate.hpp): a DEM's TIN by the quad-tree retrieval or greedy insertion, then the
// node erase.
#include "tinlod/decimate.hpp"

#include "erase/flip_pass.hpp"
#include "erase/free_heights.hpp"
#include "erase/hole_geometry.hpp"
#include "erase/tuning.hpp"
#include "tinlod/error.hpp"
#include "tinlod/greedy.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/util.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace tinlod {

using erase::k_probe_margin;
using erase::k_probe_share;
using erase::k_probe_window_min;
using erase::k_probe_window_share;
using erase::k_probe_windows;
using erase::rounding_margin;

namespace {

// Whether greedy insertion to options.max_error likely pays: the
// insertion on k_probe_windows^2 windows of full-resolution samples keeps at most k_probe_share
// of them, and a margin. The insertion's cost grows with its nodes where the erase's grows with
// the samples, so only a bound coarse enough for the terrain pays; a probe that misjudges costs the
// insertion up to max_nodes (docs/decisions/019-erase-dem-first-stage.md, 027-simplify-speed-3.md).
// It stops as soon as the windows left cannot change the answer: when they would pass even keeping
// all their samples, and within a window once it keeps more than the limit leaves
// (docs/decisions/036-simplify-speed-6.md).
static bool greedy_pays(const Heightfield &hf, const GreedyOptions &options) {
    const int bw = std::max(k_probe_window_min, hf.width / k_probe_window_share),
              bh = std::max(k_probe_window_min, hf.height / k_probe_window_share);
    if (hf.width < k_probe_windows * bw || hf.height < k_probe_windows * bh)
        return true; // too small to tell, and cheap either way
    const std::int64_t window_size = std::int64_t(bw) * bh,
                       samples = k_probe_windows * k_probe_windows * window_size;
    // The most nodes the windows may keep in all: an integer count is within the share exactly
    // when it is within this.
    const std::int64_t most =
        std::int64_t(std::floor((k_probe_share + k_probe_margin) * double(samples)));
    std::int64_t kept = 0, left = samples;
    for (int i = 0; i < k_probe_windows; ++i)
        for (int j = 0; j < k_probe_windows; ++j) {
            if (kept + left <= most)
                return true;
            Heightfield window;
            window.width = bw;
            window.height = bh;
            window.dx = hf.dx;
            window.dy = hf.dy;
            const int x0 = (hf.width - bw) * (2 * i + 1) / (2 * k_probe_windows),
                      y0 = (hf.height - bh) * (2 * j + 1) / (2 * k_probe_windows);
            window.z.reserve(std::size_t(window.size()));
            for (int r = 0; r < bh; ++r)
                for (int c = 0; c < bw; ++c)
                    window.z.push_back(hf.at(x0 + c, y0 + r));
            // The insertion's order does not depend on max_nodes: stopped at most - kept + 1
            // nodes, the window keeps at least that many.
            GreedyOptions wo = options;
            wo.max_nodes = std::min(window_size, most - kept + 1);
            kept += std::int64_t(greedy_tin(window, wo).tin.nodes.size());
            left -= window_size;
            if (kept > most)
                return false;
        }
    return true;
}

// The vertical model with a bound (no budget): greedy insertion to the bound, when the probe says
// the insertion keeps few enough samples for it and the erase after it to be faster than the erase
// from the grid; none when it does not, or when the insertion still passes greedy_cap of the
// samples. The insertion counts the erase's rounding margin (for the float coordinates farthest
// from the origin, twice: the erase measures at rounded points), so its TIN is within the bound as
// the erase measures it.
std::optional<GreedyTin> greedy_first(const Heightfield &hf, const Significance &model,
                                      const EraseOptions &options, const DemEraseOptions &dem) {
    if (model.model() != SpModel::vertical || !std::isfinite(options.tolerance) ||
        !(options.tolerance > 0.0) || options.max_nodes > 0 || !(dem.greedy_cap > 0.0))
        return std::nullopt;
    GreedyOptions go;
    go.max_error = options.tolerance;
    go.max_nodes = std::int64_t(dem.greedy_cap * double(hf.size()));
    go.slope_margin =
        2.0 * rounding_margin(std::max((hf.width - 1) * hf.dx, (hf.height - 1) * hf.dy), 1.0);
    go.seed_step = 16; // the erase drops the seed's nodes the insertion did not need
    if (!greedy_pays(hf, go))
        return std::nullopt;
    GreedyTin greedy = greedy_tin(hf, go);
    if (greedy.stopped)
        return std::nullopt;
    return greedy;
}

// The retrieval's target node count with a budget: about budget_share times the budget, at most
// half of the samples.
double retrieval_target(const Heightfield &hf, const EraseOptions &options,
                        const DemEraseOptions &dem) {
    return std::min(dem.budget_share * double(options.max_nodes), 0.5 * double(hf.size()));
}

// Whether the quad-tree retrieval goes first: the screen model only, and with a budget only when
// the target leaves the erase at least 3/4 of budget_share times the budget to choose from: a
// retrieval cut to fewer is coarse where the erase cannot mend it
// (docs/decisions/019-erase-dem-first-stage.md).
bool retrieves(const Heightfield &hf, const Significance &model, const EraseOptions &options,
               const DemEraseOptions &dem) {
    if (model.model() != SpModel::screen)
        return false;
    if (options.max_nodes <= 0)
        return dem.retrieve_share > 0.0;
    return dem.budget_share > 0.0 && retrieval_target(hf, options, dem) >=
                                         0.75 * dem.budget_share * double(options.max_nodes);
}

// A budget's retrieval: a tolerance that keeps (1, 1.2] x the target, never over the tolerance's
// share `shared` (a budget and a bound: the bound holds). The node count falls about as a power of
// the tolerance, so each step aims at 1.1 x the target along the slope of the last two retrievals
// in log-log (the first along -1), and bisects the bracket on the log when a step would leave it:
// a few retrievals, where bisection took several times as many
// (docs/decisions/019-erase-dem-first-stage.md). Leaves the tolerance in ro.tolerance; returns the
// retrieval at it, or null when the last one made was at another.
const Retrieval *retrieve_for_budget(QuadTreeLod &lod, const View &eye, RetrieveOptions &ro,
                                     double target, double shared) {
    const Retrieval *r = nullptr; // the last retrieval (it lives until the next one)
    double lo = 1e-6, hi = std::min(1e6, shared);
    double t = std::min(1.0, hi), slope = -1.0, last_t = 0.0, last_n = 0.0;
    for (int i = 0; i < 40; ++i) {
        ro.tolerance = t;
        r = &lod.retrieve(eye, ro);
        const double n = double(r->nodes.size());
        (n > target ? lo : hi) = t;
        if (n > target && n <= 1.2 * target)
            break;
        if (last_t > 0.0 && n != last_n)
            slope = std::clamp(std::log(n / last_n) / std::log(t / last_t), -4.0, -0.25);
        last_t = t;
        last_n = n;
        t *= std::exp(std::log(1.1 * target / n) / slope);
        if (!(t > lo && t < hi))
            t = std::sqrt(lo * hi);
    }
    const double last = ro.tolerance;
    ro.tolerance = std::min(lo, shared);
    return ro.tolerance == last ? r : nullptr;
}

// The quad-tree retrieval's TIN on the whole lattice (vertices for its samples only), at
// retrieve_share of the tolerance, or with a budget at the tolerance that keeps about the target.
Mesh retrieved_tin(const Heightfield &hf, const Significance &model, const EraseOptions &options,
                   const DemEraseOptions &dem, DemEraseStats &out) {
    const View &eye = *model.view();
    std::optional<QuadTree> own;
    if (!dem.tree && !dem.nodes)
        own.emplace(hf);
    std::optional<QuadTreeLod> traversal;
    if (dem.nodes)
        traversal.emplace(*dem.nodes);
    else
        traversal.emplace(dem.tree ? *dem.tree : *own);
    QuadTreeLod &lod = *traversal;
    RetrieveOptions ro;
    ro.peripheral = &model.options();
    const double shared =
        std::isfinite(options.tolerance) ? options.tolerance * dem.retrieve_share : INFINITY;
    ro.tolerance = shared;
    const Retrieval *r = nullptr;
    if (options.max_nodes > 0 && shared > 1e-6)
        r = retrieve_for_budget(lod, eye, ro, retrieval_target(hf, options, dem), shared);
    if (!r)
        r = &lod.retrieve(eye, ro);
    out.retrieved_nodes = std::int64_t(r->nodes.size());
    out.retrieve_tol = ro.tolerance;
    return to_sparse_lattice_mesh(*r, hf);
}

// One erase_dem: its inputs, and its stats as they are made.
struct DemRun {
    const Heightfield &hf;
    const Significance &model;
    const EraseOptions &options;
    const DemEraseOptions &dem;
    Stopwatch clock; // since erase_dem began, then since the erase ended
    DemEraseStats out;
};

// The erase of the first stage's TIN, and its live copy. A retrieval's or an insertion's TIN
// holds vertices for its samples only (the lattice gives the eraser the others' heights), the
// full grid one per sample.
Mesh erase_from(DemRun &run, Mesh &mesh, FirstStage stage, DemEraseStats *stats) {
    run.out.first_stage = stage;
    run.out.retrieve_ms = run.clock.ms();
    EraseOptions eo = run.options;
    eo.lattice = stage == FirstStage::grid ? nullptr : &run.hf;
    run.out.erase = NodeEraser(mesh, run.model, eo).erase();
    run.clock.reset();
    Mesh tin = live_copy(mesh);
    // At a vertical bound the nodes left may still go with a neighbouring triangle in their hole
    // (docs/decisions/026-fewer-at-fine-bounds.md), within the erase's limit, when asked for.
    if (erase::flip_pass_applies(run.model, run.options)) {
        if (run.dem.flip_pass) {
            erase::FlipPassStats pass;
            tin = erase::flip_pass(tin, run.hf, run.options.tolerance * (1.0 - 1e-6),
                                   run.options.max_valence, &pass);
            run.out.erase.erased += pass.erased;
        }
        if (!run.dem.sample_heights) {
            erase::FreeHeightsStats free;
            tin = erase::free_heights(tin, run.hf, run.options.tolerance * (1.0 - 1e-6),
                                      run.options.max_valence, &free);
            run.out.erase.erased += free.erased;
        }
        run.out.erase.output_nodes = std::int64_t(tin.n_vertices());
        run.out.erase.output_triangles = std::int64_t(tin.n_faces());
    }
    run.out.erase.erase_ms += run.clock.ms();
    if (stats)
        *stats = run.out;
    return tin;
}

} // namespace

Mesh erase_dem(const Heightfield &hf, const Significance &model, const EraseOptions &options,
               const DemEraseOptions &dem, DemEraseStats *stats) {
    // The shares a user can set, checked in Release too (EraseOptions: by the NodeEraser).
    const auto check_share = [](const char *name, double value, double hi) {
        if (!(value >= 0.0 && value <= hi))
            throw Error(std::string("DemEraseOptions::") + name,
                        "must be in [0, " + std::to_string(hi) + "], not " + std::to_string(value));
    };
    check_share("retrieve_share", dem.retrieve_share, 1.0);
    check_share("greedy_cap", dem.greedy_cap, 1.0);
    check_share("budget_share", dem.budget_share, std::numeric_limits<double>::max());
    DemRun run{hf, model, options, dem, Stopwatch(), DemEraseStats()};
    if (std::optional<GreedyTin> greedy = greedy_first(hf, model, options, dem)) {
        Mesh mesh = to_sparse_lattice_mesh(*greedy, hf);
        run.out.retrieved_nodes = std::int64_t(greedy->tin.nodes.size());
        run.out.retrieve_tol = options.tolerance;
        greedy.reset(); // the mesh holds it now: its arrays are not kept through the erase
        return erase_from(run, mesh, FirstStage::greedy, stats);
    }
    if (retrieves(hf, model, options, dem)) {
        Mesh mesh = retrieved_tin(hf, model, options, dem, run.out);
        return erase_from(run, mesh, FirstStage::quadtree, stats);
    }
    run.out.retrieved_nodes = hf.size();
    Mesh mesh = grid_tin(hf);
    return erase_from(run, mesh, FirstStage::grid, stats);
}

} // namespace tinlod
