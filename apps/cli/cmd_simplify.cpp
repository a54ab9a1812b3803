// `tinlod simplify MESH|DEM (--eye ... --at ... [--tol] [--model] | --max-error M) [--max-nodes N]
// -o OUT [--stats J]`: distance decay by node erase (lib/decimate), or its view-independent mode.
#include "commands.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/util.hpp"

#include <cmath>
#include <cstdio>
#include <optional>

namespace tinlod::cli {

static Register simplify("simplify", 40, [](CLI::App &cmd) {
    cmd.description(
        "Erase the nodes an observer cannot resolve (distance decay), or every node within "
        "a vertical bound (--max-error)");
    struct Args {
        std::string input, output, stats, model = "screen";
        double tol = 1.0;
        double max_error = 0.0;
        std::int64_t max_nodes = 0;
        double retrieve_share = DemEraseOptions{}.retrieve_share;
        CameraOptions camera;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("INPUT", args->input,
                   "DEM (GeoTIFF, PNG, EXR, .hgt, ...) or mesh (PLY, OBJ, OFF, STL)")
        ->required();
    cmd.add_option("-o,--output", args->output, "output mesh (.ply .obj .off .stl)")->required();
    cmd.add_option("--stats", args->stats, "write statistics as JSON");
    auto *tol = cmd.add_option("--tol", args->tol, "screen-space error bound tau, pixels")
                    ->capture_default_str();
    cmd.add_option("--model", args->model, "significance model: screen or paper")
        ->check(CLI::IsMember({"screen", "paper"}))
        ->capture_default_str();
    cmd.add_option(
        "--max-nodes", args->max_nodes,
        "node budget: erase until this many nodes remain (without --tol: ignore the bound)");
    auto *max_error =
        cmd.add_option("--max-error", args->max_error,
                       "view-independent: vertical error bound, world units (no camera)");
    cmd.add_option("--retrieve-share", args->retrieve_share,
                   "DEM input, screen model: the quad-tree retrieval first keeps share * tau (with "
                   "--max-nodes: about 8 x the budget, and none for a budget over 1/12 of the "
                   "samples), the node erase the rest; the bound holds at every sample either way "
                   "(0: erase from the full grid; with --max-error, 0 also skips the greedy "
                   "insertion that starts the erase where the bound is coarse for the terrain)")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    args->camera.add(cmd, false);
    args->raster.add(cmd);
    // Peak memory per DEM sample of `tinlod simplify`, measured
    // (docs/decisions/memory-per-sample.md).
    args->raster.bytes_per_sample = 130;
    return [args, tol, max_error] {
        const bool vertical = max_error->count() > 0;
        if (vertical && args->camera.given())
            throw Error("--max-error", "is view-independent: give it without --eye/--at");
        if (!vertical && (args->camera.eye.empty() || args->camera.at.empty()))
            throw Error("simplify",
                        "give --eye and --at (or --max-error for a view-independent TIN)");
        if (vertical && !(args->max_error >= 0.0 && std::isfinite(args->max_error)))
            throw Error("--max-error", "must be a finite bound >= 0");
        if (!(args->tol >= 0.0) || !std::isfinite(args->tol))
            throw Error("--tol", "must be a finite number of pixels >= 0");
        if (args->max_nodes < 0)
            throw Error("--max-nodes", "must be >= 0");
        if (!is_mesh_path(args->output))
            throw Error(args->output, "unknown mesh format (use .ply, .obj, .off or .stl)");
        check_writable({args->output, args->stats});
        std::optional<View> view;
        if (!vertical)
            view = args->camera.view();

        Stopwatch clock;
        std::optional<Heightfield> hf;
        Mesh mesh;
        if (is_mesh_path(args->input)) {
            mesh = read_mesh(args->input);
        } else {
            const LoadOptions lo = args->raster.load_options();
            hf = is_store_file(args->input) ? TileStore(args->input).heightfield()
                                            : load_heightfield(args->input, lo);
        }
        if (hf && view)
            check_eye_above(*hf, view->eye, "--eye");
        const double ms_load = clock.ms();
        std::int64_t input_nodes = std::int64_t(mesh.n_vertices());
        std::int64_t input_triangles = std::int64_t(mesh.n_faces());
        EraseOptions options;
        options.max_nodes = args->max_nodes;
        if (vertical) {
            options.significance.model = SpModel::vertical;
            options.tolerance = args->max_error;
        } else {
            options.significance.model = args->model == "paper" ? SpModel::paper : SpModel::screen;
            options.tolerance = args->max_nodes > 0 && tol->count() == 0 ? INFINITY : args->tol;
        }
        Progress bar("erase", 1000);
        options.progress = [&bar](double done) { bar.update(std::int64_t(done * 1000.0)); };
        // A DEM goes through both methods (erase_dem): the quad-tree retrieval, then the node erase
        // of the retrieved TIN over every sample of the grid.
        DemEraseStats dem;
        EraseStats erased;
        if (hf) {
            input_nodes = hf->size();
            input_triangles = 2 * std::int64_t(hf->width - 1) * (hf->height - 1);
            DemEraseOptions dem_options;
            dem_options.retrieve_share = args->retrieve_share;
            if (args->retrieve_share == 0.0) {
                dem_options.budget_share = 0.0;
                dem_options.greedy_cap = 0.0;
            }
            mesh = erase_dem(*hf, view ? &*view : nullptr, options, dem_options, &dem);
            erased = dem.erase;
        } else {
            erased = erase_nodes(mesh, view ? &*view : nullptr, options);
        }
        bar.finish();
        const double ms_simplify = erased.ms;

        clock.reset();
        write_mesh(mesh, args->output);
        const double ms_write = clock.ms();

        // Against the DEM the error is measured exhaustively; for a mesh it is the decimater's own
        // bound over every swallowed input node.
        double max_screen = erased.max_screen_px, max_vertical = erased.max_vertical;
        if (hf) {
            ErrorOptions eo;
            eo.view = view ? &*view : nullptr;
            const TinError measured = measure_error(*hf, mesh, eo);
            max_screen = measured.max_screen_px;
            max_vertical = measured.max_vertical;
        }
        nlohmann::json stats = {
            {"input",
             {{"file", args->input}, {"nodes", input_nodes}, {"triangles", input_triangles}}},
            {"output",
             {{"file", args->output}, {"nodes", mesh.n_vertices()}, {"triangles", mesh.n_faces()}}},
            {"time_ms",
             {{"load", ms_load},
              {"retrieve", dem.retrieve_ms},
              {"simplify", ms_simplify},
              {"write", ms_write}}},
            {"retrieve",
             {{"first_stage", first_stage_name(dem.first_stage)},
              {"tol", dem.retrieve_tol},
              {"nodes", hf ? dem.retrieved_nodes : 0}}},
            {"error", {{"max_screen_px", max_screen}, {"max_vertical", max_vertical}}},
            {"simplify",
             {{"model", vertical ? "vertical" : args->model},
              {"tolerance", std::isfinite(options.tolerance) ? options.tolerance : -1.0},
              {"max_nodes", args->max_nodes},
              {"erased", erased.erased},
              {"evaluations", erased.evaluations},
              {"bound_reached", erased.max_weighted}}},
            {"peak_rss_mb", peak_rss_mb()}};
        if (!args->stats.empty())
            write_json(args->stats, stats);
        // A mesh's deviation is vertical only when it is a TIN (a node's distance to the surface
        // otherwise, see EraseStats::max_vertical).
        std::printf("%s: %zu nodes, %zu triangles (from %lld nodes) in %.0f ms; max error %.3g px, "
                    "%.3g %s\n",
                    args->output.c_str(), mesh.n_vertices(), mesh.n_faces(),
                    static_cast<long long>(input_nodes), ms_simplify, max_screen, max_vertical,
                    hf ? "vertical" : "deviation");
    };
});

} // namespace tinlod::cli
