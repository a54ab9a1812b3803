// `tinlod build DEM -o STORE`: the quad-tree store on disk (lib/store), with a progress bar.
#include "commands.hpp"
#include "outputs.hpp"

#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/util.hpp"

#include <cstdio>
#include <utility>

namespace tinlod::cli {

static Register build("build", 20, [](CLI::App &cmd) {
    cmd.description(
        "Write the quad-tree store of a DEM (.tlq): elevations in tiles, node error bounds, "
        "checksums; `retrieve` reads it partially");
    struct Args {
        std::string input, output, stats;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("DEM", args->input, "DEM file (GeoTIFF, PNG, EXR, .hgt, ...) or store")
        ->required();
    cmd.add_option("-o,--output", args->output, "store file to write (.tlq)")->required();
    cmd.add_option("--stats", args->stats, "write statistics as JSON");
    args->raster.add(cmd);
    declare_outputs(cmd, {{"--output", &args->output}, {"--stats", &args->stats}});
    return [args] {
        if (is_mesh_path(args->output))
            throw UsageError(args->output, "a store is not a mesh file; name it .tlq");
        check_store_writable(args->output);
        check_writable({args->stats});
        StageTimes times;
        Heightfield hf = args->raster.load(args->input);
        times.lap("load");
        const int levels = QuadLayout(hf.width, hf.height).levels();
        Progress bounds_bar("bounds", hf.size() * std::max(levels - 1, 1));
        // The tree takes the elevations over: the raster is not held twice.
        const QuadTree tree(std::move(hf), &bounds_bar);
        const GridFrame &grid = tree.frame(); // hf gave its elevations away
        const std::int64_t samples = std::int64_t(grid.width) * grid.height;
        bounds_bar.finish();
        const double ms_bounds = times.lap("bounds");
        Progress write_bar("write ", std::int64_t(grid.width - 1) * (grid.height - 1));
        write_store(tree, args->output, &write_bar);
        write_bar.finish();
        const double ms_write = times.lap("write");
        const TileStore store(args->output);
        times.lap("reopen");
        const double samples_per_s = double(samples) / ((ms_bounds + ms_write) / 1000.0);
        if (!args->stats.empty())
            write_json(args->stats, {{"input",
                                      {{"file", args->input},
                                       {"nodes", samples},
                                       {"width", grid.width},
                                       {"height", grid.height}}},
                                     {"output",
                                      {{"file", args->output},
                                       {"bytes", store.file_bytes()},
                                       {"levels", levels},
                                       {"tile_level", store.tile_level()},
                                       {"tiles", store.tile_count()},
                                       {"tree_nodes", tree.node_count()}}},
                                     {"time_ms", times.json()},
                                     {"build_samples_per_s", samples_per_s},
                                     {"threads", max_threads()},
                                     {"peak_rss_mb", peak_rss_mb()}});
        std::printf("%s: %dx%d samples, %d levels, %lld tiles, %.1f MB in %s (%.1f M samples/s)\n",
                    args->output.c_str(), grid.width, grid.height, levels,
                    static_cast<long long>(store.tile_count()), store.file_bytes() / 1e6,
                    times.summary().c_str(), samples_per_s / 1e6);
    };
});

} // namespace tinlod::cli
