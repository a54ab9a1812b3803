// `tinlod simplify MESH|DEM|STORE (--eye ... --at ... [--tol] [--model] [--max-nodes N] |
// [--max-error M] [--max-nodes N] [--max-triangles T]) -o OUT [--stats J]`: distance decay by node
// erase (lib/decimate), or its view-independent modes: a vertical bound (node erase) or a budget
// of nodes or triangles (greedy insertion, lib/greedy, as the heightmap meshers hmm and delatin).
#include "commands.hpp"
#include "outputs.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/error.hpp"
#include "tinlod/greedy.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/store_erase.hpp"
#include "tinlod/util.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

namespace tinlod::cli {

// Greedy insertion by largest vertical error until the budget (or the bound, when one is given:
// whichever comes first). Without a bound it goes on until every sample is within float noise of
// the TIN, 2^-30 of the height range (greedy_tin's queue needs a threshold above 0), and the queue
// orders to 1 % (64 buckets per octave over those 30 octaves): the error the budget reaches is the
// greedy order's, not up to 41 % over it (N42E001 to 10,000 nodes: 154.3 m, 171.9 at 2).
static GreedyTin greedy_to_budget(const Heightfield &hf, double max_error, std::int64_t max_nodes,
                                  std::int64_t max_triangles) {
    GreedyOptions go;
    const double range = double(hf.max_z()) - double(hf.min_z());
    go.max_error = max_error > 0.0 ? max_error : range > 0.0 ? std::ldexp(range, -30) : 1.0;
    go.buckets_per_octave = 64;
    go.max_nodes = max_nodes;
    go.max_triangles = max_triangles;
    return greedy_tin(hf, go);
}

static Register simplify("simplify", 40, [](CLI::App &cmd) {
    cmd.description(
        "Erase the nodes an observer cannot resolve (distance decay), or, without a camera, make "
        "the TIN within a vertical bound (--max-error) or of a budget (--max-nodes, "
        "--max-triangles)");
    struct Args {
        std::string input, output, stats, model = "screen";
        double tol = 1.0;
        double max_error = 0.0;
        std::int64_t max_nodes = 0, max_triangles = 0;
        double retrieve_share = DemEraseOptions{}.retrieve_share;
        double cache_mb = StoreOptions{}.cache_mb;
        bool sample_heights = false;
        bool flip_pass = false;
        CameraOptions camera;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("INPUT", args->input,
                   "DEM (GeoTIFF, PNG, EXR, .hgt, ...), quad-tree store (.tlq) or mesh (PLY, OBJ, "
                   "OFF, STL)")
        ->required();
    cmd.add_option("-o,--output", args->output, "output mesh (.ply .obj .off .stl)")->required();
    cmd.add_option("--stats", args->stats, "write statistics as JSON");
    declare_outputs(cmd, {{"--output", &args->output}, {"--stats", &args->stats}});
    auto *tol = cmd.add_option("--tol", args->tol, "screen-space error bound tau, pixels")
                    ->check(real_in(0.0, INFINITY))
                    ->capture_default_str();
    auto *model = cmd.add_option("--model", args->model, "significance model: screen or paper")
                      ->check(CLI::IsMember({"screen", "paper"}))
                      ->capture_default_str();
    auto *max_nodes =
        cmd.add_option("--max-nodes", args->max_nodes,
                       "node budget. With a camera: erase until this many nodes remain (without "
                       "--tol: ignore the bound). Without: exactly this many nodes (at least 4, "
                       "the corners), inserted greedily by largest vertical error (the DEM's)")
            ->check(whole_in(1, std::int64_t(1) << 40));
    auto *max_triangles =
        cmd.add_option("--max-triangles", args->max_triangles,
                       "DEM, without a camera: triangle budget (at least 2), as --max-nodes; an "
                       "insertion inside adds two, so the count is the budget or one under it")
            ->check(whole_in(2, std::int64_t(1) << 40));
    auto *max_error = cmd.add_option(
        "--max-error", args->max_error,
        "view-independent: vertical error bound, world units (no camera). With a budget: stop at "
        "whichever comes first");
    max_error->check(real_in(0.0, INFINITY));
    auto *share =
        cmd.add_option("--retrieve-share", args->retrieve_share,
                       "DEM input, screen model: the quad-tree retrieval first keeps share * tau "
                       "(with --max-nodes: about 8 x the budget, and none for a budget over 1/12 "
                       "of the samples), the node erase the rest; the bound holds at every sample "
                       "either way (0: erase from the full grid; with --max-error, 0 also skips "
                       "the greedy insertion that starts the erase where the bound is coarse for "
                       "the terrain)")
            ->check(real_in(0.0, 1.0))
            ->capture_default_str();
    cmd.add_flag("--sample-heights", args->sample_heights,
                 "DEM with --max-error alone: keep every node on its sample's height (by default "
                 "the last pass moves interior nodes' heights within the bound to erase more)");
    cmd.add_flag("--flip-pass", args->flip_pass,
                 "DEM with --max-error alone: after the erase, try every node left again with "
                 "its hole widened by a neighbouring triangle (0.4-3.1 % fewer triangles for "
                 "1.1-1.7 x the time)");
    cmd.add_option("--cache-mb", args->cache_mb,
                   "store input with a camera: store tiles the retrieval (and with --tol alone, "
                   "the erase) keeps in memory, MiB")
        ->check(real_in(0.0, INFINITY))
        ->capture_default_str();
    args->camera.add(cmd, false);
    args->raster.add(cmd);
    // Peak memory per DEM sample of `tinlod simplify`, measured
    // (docs/decisions/memory-per-sample.md).
    args->raster.bytes_per_sample = 130;
    return [args, tol, model, max_nodes, max_triangles, max_error, share] {
        const bool bound = max_error->count() > 0;
        const bool budget = max_nodes->count() > 0 || max_triangles->count() > 0;
        const bool has_camera = args->camera.given();
        const bool mesh_input = is_mesh_path(args->input);
        if (has_camera && (args->camera.eye.empty() || args->camera.at.empty()))
            throw UsageError("simplify", "give both --eye and --at");
        if (has_camera && bound)
            throw UsageError("--max-error", "is view-independent: give it without --eye/--at");
        if (has_camera && max_triangles->count() > 0)
            throw UsageError("--max-triangles", "is view-independent: give it without --eye/--at");
        if (!has_camera && !bound && !budget)
            throw UsageError("simplify", "give --eye and --at, or --max-error, --max-nodes or "
                                         "--max-triangles for a view-independent TIN");
        if (!has_camera) {
            for (const CLI::Option *o : {tol, model})
                if (o->count() > 0)
                    throw UsageError(o->get_name(), "applies to a view: give it with --eye/--at");
        }
        // Without a camera a budget on a DEM is greedy insertion: it starts from the 4 corners.
        const bool greedy = !has_camera && budget && !mesh_input;
        if (greedy && max_nodes->count() > 0 && args->max_nodes < 4)
            throw UsageError("--max-nodes",
                             "a TIN over the DEM keeps its 4 corners: give 4 or more");
        if (greedy && share->count() > 0)
            throw UsageError("--retrieve-share", "has no retrieval to share with a budget and no "
                                                 "camera (greedy insertion)");
        if (mesh_input && max_triangles->count() > 0)
            throw UsageError("--max-triangles", "needs a DEM or store input, not a mesh");
        if (!is_mesh_path(args->output))
            throw UsageError(args->output, "unknown mesh format (use .ply, .obj, .off or .stl)");
        check_writable({args->output, args->stats});
        std::optional<View> view;
        if (has_camera)
            view = args->camera.view();

        // A store seen with a tolerance alone (screen model, a retrieval share) is never read
        // whole: erase_store tests triangles through its quad-tree and tile cache
        // (docs/decisions/031-bounded-store-erase.md). A budget, the paper model or
        // --retrieve-share 0 read its heights whole, as a DEM's.
        const bool bounded_store = !mesh_input && is_store_path(args->input) && has_camera &&
                                   max_nodes->count() == 0 && args->model == "screen" &&
                                   args->retrieve_share > 0.0;
        StageTimes times;
        std::optional<Heightfield> hf;
        std::optional<TileStore> store;
        Mesh mesh;
        if (mesh_input) {
            mesh = read_mesh(args->input);
        } else if (bounded_store) {
            args->raster.check_store(args->input);
            StoreOptions so;
            so.cache_mb = args->cache_mb;
            store.emplace(args->input, so);
            check_eye_above(*store, view->eye, "--eye");
        } else {
            hf = args->raster.load(args->input);
        }
        if (hf && view)
            check_eye_above(*hf, view->eye, "--eye");
        times.lap("load");
        std::int64_t input_nodes = std::int64_t(mesh.n_vertices());
        std::int64_t input_triangles = std::int64_t(mesh.n_faces());
        if (hf || store) {
            const std::int64_t w = hf ? hf->width : store->frame().width,
                               h = hf ? hf->height : store->frame().height;
            input_nodes = w * h;
            input_triangles = 2 * (w - 1) * (h - 1);
        }
        EraseOptions options;
        options.max_nodes = args->max_nodes;
        Significance model;
        if (!has_camera) {
            options.tolerance = bound ? args->max_error : INFINITY;
        } else {
            model =
                args->model == "paper" ? Significance::paper(*view) : Significance::screen(*view);
            options.tolerance = args->max_nodes > 0 && tol->count() == 0 ? INFINITY : args->tol;
        }
        DemEraseStats dem;
        EraseStats erased;
        bool stopped_by_budget = false;
        if (greedy) {
            const GreedyTin g =
                greedy_to_budget(*hf, args->max_error, args->max_nodes, args->max_triangles);
            times.lap("retrieve");
            stopped_by_budget = g.stopped;
            dem.first_stage = FirstStage::greedy;
            dem.retrieved_nodes = std::int64_t(g.tin.nodes.size());
            dem.retrieve_tol = bound ? args->max_error : 0.0;
            mesh = tin_from_indices(*hf, g.tin.triangles);
            times.lap("convert");
        } else {
            Progress bar("erase", 1000);
            options.progress = [&bar](double done) { bar.update(std::int64_t(done * 1000.0)); };
            // A DEM goes through both methods (erase_dem): the quad-tree retrieval (or the greedy
            // insertion), then the node erase of its TIN over every sample of the grid.
            if (store) {
                mesh = erase_store(*store, model, options.tolerance, args->retrieve_share, &dem);
                erased = dem.erase;
                // Its erase tests thresholds and keeps no maximum: the stats' bound_reached is
                // null, the error below the measured one.
                erased.max_weighted = NAN;
                times.add("retrieve", dem.retrieve_ms);
            } else if (hf) {
                DemEraseOptions dem_options;
                // A store holds the quad-tree's bounds: the retrieval reads them, tile by tile,
                // instead of building them again from the heights.
                std::optional<TileStore> nodes;
                if (is_store_path(args->input)) {
                    StoreOptions so;
                    so.cache_mb = args->cache_mb;
                    nodes.emplace(args->input, so);
                    dem_options.nodes = &*nodes;
                }
                dem_options.retrieve_share = args->retrieve_share;
                dem_options.sample_heights = args->sample_heights;
                dem_options.flip_pass = args->flip_pass;
                if (args->retrieve_share == 0.0) {
                    dem_options.budget_share = 0.0;
                    dem_options.greedy_cap = 0.0;
                }
                mesh = erase_dem(*hf, model, options, dem_options, &dem);
                erased = dem.erase;
                times.add("retrieve", dem.retrieve_ms);
            } else {
                erased = erase_nodes(mesh, model, options);
            }
            bar.finish();
            times.lap("simplify");
            stopped_by_budget =
                args->max_nodes > 0 && std::int64_t(mesh.n_vertices()) <= args->max_nodes;
        }

        // Against the DEM the error is measured exhaustively; for a mesh it is the decimater's own
        // bound over every swallowed input node.
        double max_screen = erased.max_screen_px, max_vertical = erased.max_vertical;
        if (hf || store) {
            ErrorOptions eo;
            eo.model = model;
            const TinError measured =
                hf ? measure_error(*hf, mesh, eo) : measure_store_error(*store, mesh, eo);
            max_screen = measured.max_screen_px;
            max_vertical = measured.max_vertical;
            times.lap("measure");
        }
        write_mesh(mesh, args->output);
        times.lap("write");

        nlohmann::json stats = {
            {"input",
             {{"file", args->input}, {"nodes", input_nodes}, {"triangles", input_triangles}}},
            {"output",
             {{"file", args->output}, {"nodes", mesh.n_vertices()}, {"triangles", mesh.n_faces()}}},
            {"time_ms", times.json()},
            {"error",
             {{"max_screen_px", view ? nlohmann::json(max_screen) : nlohmann::json()},
              {"max_vertical", max_vertical}}},
            {"simplify",
             {{"model", has_camera ? args->model : "vertical"},
              {"method", greedy ? "greedy insertion" : "node erase"},
              {"tolerance", std::isfinite(options.tolerance) ? options.tolerance : -1.0},
              {"max_nodes", args->max_nodes},
              {"max_triangles", args->max_triangles},
              {"stopped_by", stopped_by_budget ? "budget" : "bound"},
              {"erased", erased.erased},
              {"evaluations", erased.evaluations},
              {"bound_reached", erased.max_weighted}}},
            {"peak_rss_mb", peak_rss_mb()}};
        // What the erase started from: a DEM's first stage (a mesh has none).
        if (hf || store)
            stats["retrieve"] = {{"first_stage", first_stage_name(dem.first_stage)},
                                 {"tol", dem.retrieve_tol},
                                 {"nodes", dem.retrieved_nodes}};
        if (!args->stats.empty())
            write_json(args->stats, stats);

        // The first stage's time is named by what it was; a mesh's deviation is vertical only when
        // it is a TIN (a node's distance to the surface otherwise, see EraseStats::max_vertical).
        StageTimes shown = times;
        shown.rename("retrieve", first_stage_name(dem.first_stage));
        const char *deviation = hf || store ? "vertical error" : "deviation";
        char text[160];
        if (view)
            std::snprintf(text, sizeof text, "max error %.3g px on screen, max %s %.3g m",
                          max_screen, deviation, max_vertical);
        else
            std::snprintf(text, sizeof text, "max %s %.4g m", deviation, max_vertical);
        std::string error = text;
        const bool bounded = std::isfinite(options.tolerance);
        if (budget && stopped_by_budget && bounded)
            error += " (the budget came first)";
        else if (budget && !stopped_by_budget)
            error += bounded  ? " (the bound came first)"
                     : greedy ? " (every sample is on the TIN: fewer nodes than the budget)"
                              : " (no more nodes could be erased: over the budget)";
        std::printf("%s: %zu nodes, %zu triangles (from %lld nodes) in %s; %s\n",
                    args->output.c_str(), mesh.n_vertices(), mesh.n_faces(),
                    static_cast<long long>(input_nodes), shown.summary().c_str(), error.c_str());
    };
});

} // namespace tinlod::cli
