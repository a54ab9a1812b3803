// `tinlod retrieve DEM --full -o OUT [--stats J]`: the full-resolution TIN of a DEM.
#include "commands.hpp"

#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/util.hpp"

#include <cstdio>

namespace tinlod::cli {

static Register retrieve("retrieve", 30, [](CLI::App& cmd) {
    cmd.description("Build a TIN from a DEM: the full grid (--full)");
    struct Args {
        std::string input, output, stats;
        bool full = false;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("INPUT", args->input, "DEM file")->required();
    cmd.add_option("-o,--output", args->output, "output mesh (.ply .obj .off .stl)")->required();
    cmd.add_option("--stats", args->stats, "write statistics as JSON");
    cmd.add_flag("--full", args->full, "the full-resolution grid TIN (no level of detail)");
    args->raster.add(cmd);
    return [args] {
        if (!args->full)
            throw Error("retrieve", "give --full (view-dependent retrieval needs --eye and --at)");
        if (!is_mesh_path(args->output))
            throw Error(args->output, "unknown mesh format (use .ply, .obj, .off or .stl)");
        Stopwatch clock;
        LoadOptions lo;
        lo.cell = args->raster.cell;
        lo.zscale = args->raster.zscale;
        lo.terrain_rgb = args->raster.terrain_rgb;
        const Heightfield hf = load_heightfield(args->input, lo);
        const double ms_load = clock.ms();
        clock.reset();
        const Mesh mesh = grid_tin(hf);
        const double ms_retrieve = clock.ms();
        clock.reset();
        write_mesh(mesh, args->output);
        const double ms_write = clock.ms();
        nlohmann::json stats = {
            {"input", {{"file", args->input}, {"nodes", hf.size()},
                       {"triangles", 2 * std::int64_t(hf.width - 1) * (hf.height - 1)},
                       {"voids", hf.voids}, {"voids_filled", hf.filled}}},
            {"output", {{"file", args->output}, {"nodes", mesh.n_vertices()},
                        {"triangles", mesh.n_faces()}}},
            {"time_ms", {{"load", ms_load}, {"retrieve", ms_retrieve}, {"write", ms_write}}},
            {"error", {{"max_screen_px", 0.0}, {"max_vertical", 0.0}}},
            {"peak_rss_mb", peak_rss_mb()}};
        if (!args->stats.empty())
            write_json(args->stats, stats);
        std::printf("%s: %zu nodes, %zu triangles (full grid %dx%d) in %.0f ms\n",
                    args->output.c_str(), mesh.n_vertices(), mesh.n_faces(), hf.width, hf.height,
                    ms_load + ms_retrieve + ms_write);
    };
});

} // namespace tinlod::cli
