// `tinlod retrieve DEM|STORE (--eye X,Y,Z --at X,Y,Z [--fov] [--viewport] [--tol] [--cull] |
// --full) -o OUT [--stats J] [--check] [--cache-mb M]`: the view-dependent TIN of the quad-tree
// (lib/quadtree), from a DEM in memory or partially from a store (lib/store), or the
// full-resolution grid.
#include "commands.hpp"
#include "outputs.hpp"

#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/util.hpp"

#include <cmath>
#include <cstdio>
#include <optional>

namespace tinlod::cli {

// Height of the retrieved surface under the eye, if the eye stands over the terrain.
static std::optional<double> surface_under(const Retrieval &r, const GridFrame &frame,
                                           const glm::dvec3 &eye) {
    const double u = eye.x / frame.dx, v = eye.y / frame.dy;
    if (!(u >= 0 && v >= 0 && u <= frame.width - 1 && v <= frame.height - 1))
        return std::nullopt;
    const auto w = static_cast<std::uint32_t>(frame.width);
    auto z_of = [&](std::uint32_t id) {
        for (std::size_t n = 0; n < r.nodes.size(); ++n)
            if (r.nodes[n] == id)
                return double(r.z[n]);
        return 0.0;
    };
    for (std::size_t t = 0; t + 2 < r.triangles.size(); t += 3) {
        double pu[3], pv[3];
        for (int k = 0; k < 3; ++k) {
            pu[k] = r.triangles[t + k] % w;
            pv[k] = r.triangles[t + k] / w;
        }
        const double area = (pu[1] - pu[0]) * (pv[2] - pv[0]) - (pu[2] - pu[0]) * (pv[1] - pv[0]);
        const double w0 = ((pu[1] - u) * (pv[2] - v) - (pu[2] - u) * (pv[1] - v)) / area;
        const double w1 = ((pu[2] - u) * (pv[0] - v) - (pu[0] - u) * (pv[2] - v)) / area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 >= -1e-9 && w1 >= -1e-9 && w2 >= -1e-9)
            return w0 * z_of(r.triangles[t]) + w1 * z_of(r.triangles[t + 1]) +
                   w2 * z_of(r.triangles[t + 2]);
    }
    return std::nullopt;
}

static Register retrieve("retrieve", 30, [](CLI::App &cmd) {
    cmd.description(
        "Retrieve the view-dependent TIN of a DEM or store (screen-space error <= --tol), "
        "or the full grid (--full)");
    struct Args {
        std::string input, output, stats;
        bool full = false, cull = false, check = false;
        double tol = 1.0, cache_mb = 256.0;
        CameraOptions camera;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("INPUT", args->input, "DEM file, or a store written by `tinlod build` (.tlq)")
        ->required();
    cmd.add_option("-o,--output", args->output, "output mesh (.ply .obj .off .stl)")->required();
    cmd.add_option("--stats", args->stats, "write statistics as JSON");
    declare_outputs(cmd, {{"--output", &args->output}, {"--stats", &args->stats}});
    cmd.add_flag("--full", args->full, "the full-resolution grid TIN (no level of detail)");
    cmd.add_option("--tol", args->tol, "screen-space error bound tau, pixels")
        ->check(real_in(0.0, INFINITY))
        ->capture_default_str();
    cmd.add_flag("--cull", args->cull, "leave the terrain outside the view frustum coarse");
    cmd.add_flag("--check", args->check,
                 "measure the error exhaustively over every sample (error.max_screen_px)");
    cmd.add_option("--cache-mb", args->cache_mb, "store tiles kept in memory, MiB")
        ->check(real_in(0.0, 1e9))
        ->capture_default_str();
    args->camera.add(cmd, false);
    args->raster.add(cmd);
    return [args] {
        if (!is_mesh_path(args->output))
            throw UsageError(args->output, "unknown mesh format (use .ply, .obj, .off or .stl)");
        if (args->full && args->camera.given())
            throw UsageError("--full", "takes no camera: give either --full or --eye/--at");
        if (!args->full && (args->camera.eye.empty() || args->camera.at.empty()))
            throw UsageError("retrieve", "give --eye and --at (or --full for the whole grid)");
        check_writable({args->output, args->stats});
        std::optional<View> view;
        if (!args->full)
            view = args->camera.view();

        StageTimes times;
        std::optional<Heightfield> hf;
        std::optional<QuadTree> tree;
        TileStore *store = nullptr;
        std::unique_ptr<QuadTreeLod> lod;
        const bool from_store = is_store_path(args->input);
        if (from_store) {
            args->raster.check_store(args->input);
            StoreOptions so;
            so.cache_mb = args->cache_mb;
            auto owned = std::make_unique<TileStore>(args->input, so);
            store = owned.get();
            if (args->full)
                hf = store->heightfield();
            else
                lod = std::make_unique<QuadTreeLod>(std::move(owned));
            times.lap("load");
        } else {
            LoadOptions lo = args->raster.load_options();
            // Peak memory per DEM sample, measured (docs/decisions/memory-per-sample.md): the
            // full grid as a mesh, or the quad-tree and one view's TIN.
            lo.bytes_per_sample = args->full ? 340 : 120;
            hf = load_heightfield(args->input, lo);
            times.lap("load");
            if (!args->full) {
                tree.emplace(*hf);
                lod = std::make_unique<QuadTreeLod>(*tree);
                times.lap("build");
            }
        }
        const GridFrame frame =
            lod ? lod->frame() : GridFrame{hf->width,    hf->height,   hf->dx, hf->dy,
                                           hf->origin_x, hf->origin_y, hf->crs};
        const std::int64_t grid_nodes = std::int64_t(frame.width) * frame.height;
        const std::int64_t grid_triangles = 2 * std::int64_t(frame.width - 1) * (frame.height - 1);

        Mesh mesh;
        nlohmann::json stats;
        std::vector<std::uint32_t> triangles;
        if (args->full) {
            mesh = grid_tin(*hf);
            times.lap("retrieve");
            stats["error"] = {{"max_screen_px", 0.0}, {"max_vertical", 0.0}, {"measured", true}};
        } else {
            RetrieveOptions ro;
            ro.tolerance = args->tol;
            ro.cull = args->cull;
            const Retrieval &r = lod->retrieve(*view, ro);
            times.lap("retrieve");
            if (const auto ground = surface_under(r, frame, view->eye);
                ground && view->eye.z < *ground)
                throw Error("--eye", "the eye is below the terrain surface (" +
                                         std::to_string(*ground) + " there)");
            mesh = to_mesh(r, frame);
            times.lap("convert");
            triangles = r.triangles;
            stats["retrieve"] = {{"tol_px", args->tol},
                                 {"cull", args->cull},
                                 {"bound_px", r.bound_px},
                                 {"tree_nodes", r.tree_nodes},
                                 {"leaves", r.leaves},
                                 {"forced_splits", r.forced},
                                 {"node_ratio", double(r.nodes.size()) / grid_nodes}};
            stats["error"] = {{"max_screen_px", r.bound_px}, {"measured", false}};
            if (store)
                stats["store"] = {{"tiles_read", store->last_stats().tiles_read},
                                  {"bytes_read", store->last_stats().bytes_read},
                                  {"tiles_total", store->tile_count()},
                                  {"tiles_resident", store->resident_tiles()},
                                  {"tiles_evicted", store->last_stats().tiles_evicted},
                                  {"file_bytes", store->file_bytes()},
                                  {"cache_mb", args->cache_mb}};
        }
        write_mesh(mesh, args->output);
        times.lap("write");

        if (args->check && !args->full) {
            if (!hf)
                hf = store->heightfield();
            ErrorOptions eo;
            eo.view = &*view;
            eo.frustum_only = true;
            const TinError in_view = measure_error(*hf, triangles, eo);
            eo.frustum_only = false;
            const TinError all = measure_error(*hf, triangles, eo);
            stats["error"] = {{"max_screen_px", in_view.max_screen_px},
                              {"max_screen_px_all_samples", all.max_screen_px},
                              {"max_vertical", all.max_vertical},
                              {"rms_vertical", all.rms_vertical},
                              {"uncovered_samples", all.uncovered},
                              {"bound_px", stats["retrieve"]["bound_px"]},
                              {"measured", true}};
            times.lap("check");
        }
        stats["input"] = {{"file", args->input},
                          {"kind", from_store ? "store" : "raster"},
                          {"nodes", grid_nodes},
                          {"triangles", grid_triangles}};
        stats["output"] = {
            {"file", args->output}, {"nodes", mesh.n_vertices()}, {"triangles", mesh.n_faces()}};
        stats["time_ms"] = times.json();
        stats["peak_rss_mb"] = peak_rss_mb();
        if (!args->stats.empty())
            write_json(args->stats, stats);
        std::printf("%s: %zu nodes (%.2f%% of the %dx%d grid), %zu triangles", args->output.c_str(),
                    mesh.n_vertices(), 100.0 * double(mesh.n_vertices()) / grid_nodes, frame.width,
                    frame.height, mesh.n_faces());
        if (!args->full)
            std::printf(", screen error %s %.3f px (tol %.3g)",
                        stats["error"]["measured"].get<bool>() ? "measured" : "bound",
                        stats["error"]["max_screen_px"].get<double>(), args->tol);
        if (store && !args->full)
            std::printf(", %lld of %lld tiles read",
                        static_cast<long long>(store->last_stats().tiles_read),
                        static_cast<long long>(store->tile_count()));
        std::printf(" in %s\n", times.summary().c_str());
    };
});

} // namespace tinlod::cli
