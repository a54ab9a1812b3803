// `tinlod build DEM -o STORE [--memory-mb M]`: the quad-tree store on disk (lib/store), with a
// progress bar; a DEM larger than the memory given is read by windows and written tile by tile.
#include "commands.hpp"
#include "outputs.hpp"

#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/tiles.hpp"
#include "tinlod/util.hpp"

#include <cstdio>
#include <utility>

namespace tinlod::cli {

// Peak memory of the whole-raster build per sample, bytes: the heights, the node bounds (12 bytes
// per node, a third of a node per sample) and the loader's buffers
// (docs/decisions/memory-per-sample.md measured 15).
constexpr double k_whole_bytes_per_sample = 16.0;
// Memory of the run besides its heights, MiB: the program, the top tree and the corner
// elevations, the tiles of a tile row.
constexpr double k_fixed_mb = 48.0;
constexpr double k_mib = 1024.0 * 1024.0;

// Whether the whole-raster build would pass memory_mb: then the DEM is read by windows. A raster
// whose size cannot be read goes the whole way, whose loader names the problem.
static bool by_windows(const std::string &input, double memory_mb) {
    if (is_store_path(input))
        return false;
    try {
        return double(raster_samples(input)) * k_whole_bytes_per_sample / k_mib + k_fixed_mb >
               memory_mb;
    } catch (const Error &) {
        return false;
    }
}

static Register build("build", 20, [](CLI::App &cmd) {
    cmd.description(
        "Write the quad-tree store of a DEM (.tlq): elevations in tiles, node error bounds, "
        "checksums; `retrieve` reads it partially");
    struct Args {
        std::string input, output, stats;
        double memory_mb = 0.0;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("DEM", args->input, "DEM file (GeoTIFF, PNG, EXR, .hgt, ...) or store")
        ->required();
    cmd.add_option("-o,--output", args->output, "store file to write (.tlq)")->required();
    cmd.add_option("--stats", args->stats, "write statistics as JSON");
    cmd.add_option("--memory-mb", args->memory_mb,
                   "memory the run may hold, MiB: past it the DEM is read by windows, bands of "
                   "tile rows, and the store written tile by tile, the same bytes (default: half "
                   "of this machine's memory)")
        ->check(real_in(1.0, 1e9));
    args->raster.add(cmd);
    declare_outputs(cmd, {{"--output", &args->output}, {"--stats", &args->stats}});
    return [args] {
        args->raster.refuse_max_memory("build");
        if (is_mesh_path(args->output))
            throw UsageError(args->output, "a store is not a mesh file; name it .tlq");
        check_store_writable(args->output);
        check_writable({args->stats});
        StageTimes times;
        const double memory_mb = args->memory_mb > 0 ? args->memory_mb : default_memory_mb();
        double ms_build = 0.0;
        std::int64_t tree_nodes = 0;
        GridFrame grid;
        const bool windows = by_windows(args->input, memory_mb);
        if (windows) {
            const DemWindows dem(args->input, args->raster.load_options());
            const Heightfield &hf = dem.grid();
            grid = {hf.width, hf.height, hf.dx, hf.dy, hf.origin_x, hf.origin_y, hf.crs};
            times.lap("load");
            // A band's heights take a quarter of the rest: the next band is read (with the reader's
            // buffers) while the last is still held.
            const auto band_bytes =
                std::int64_t(std::max(memory_mb - k_fixed_mb, 1.0) * k_mib / 4.0);
            Progress bar("build ", 2 * std::int64_t(grid.height - 1));
            write_store_by_rows(
                grid, [&dem](int r0, int r1) { return dem.rows(r0, r1); }, band_bytes, args->output,
                &bar);
            bar.finish();
            ms_build = times.lap("build");
            const QuadLayout layout(grid.width, grid.height);
            for (int d = 0; d + 1 < layout.levels(); ++d)
                tree_nodes += std::int64_t(layout.level_nodes(d));
        } else {
            Heightfield hf = args->raster.load(args->input);
            times.lap("load");
            const int levels = QuadLayout(hf.width, hf.height).levels();
            Progress bounds_bar("bounds", hf.size() * std::max(levels - 1, 1));
            // The tree takes the elevations over: the raster is not held twice.
            const QuadTree tree(std::move(hf), &bounds_bar);
            grid = tree.frame(); // hf gave its elevations away
            tree_nodes = tree.node_count();
            bounds_bar.finish();
            ms_build = times.lap("bounds");
            Progress write_bar("write ", std::int64_t(grid.width - 1) * (grid.height - 1));
            write_store(tree, args->output, &write_bar);
            write_bar.finish();
            ms_build += times.lap("write");
        }
        const std::int64_t samples = std::int64_t(grid.width) * grid.height;
        const int levels = QuadLayout(grid.width, grid.height).levels();
        const TileStore store(args->output);
        times.lap("reopen");
        const double samples_per_s = double(samples) / (ms_build / 1000.0);
        if (!args->stats.empty())
            write_json(args->stats, {{"input",
                                      {{"file", args->input},
                                       {"nodes", samples},
                                       {"width", grid.width},
                                       {"height", grid.height},
                                       {"read", windows ? "by windows" : "whole"}}},
                                     {"output",
                                      {{"file", args->output},
                                       {"bytes", store.file_bytes()},
                                       {"levels", levels},
                                       {"tile_level", store.tile_level()},
                                       {"tiles", store.tile_count()},
                                       {"tree_nodes", tree_nodes}}},
                                     {"time_ms", times.json()},
                                     {"build_samples_per_s", samples_per_s},
                                     {"threads", max_threads()},
                                     {"memory_mb", memory_mb},
                                     {"peak_rss_mb", peak_rss_mb()}});
        std::printf("%s: %dx%d samples, %d levels, %lld tiles, %.1f MB in %s (%.1f M samples/s)\n",
                    args->output.c_str(), grid.width, grid.height, levels,
                    static_cast<long long>(store.tile_count()), store.file_bytes() / 1e6,
                    times.summary().c_str(), samples_per_s / 1e6);
    };
});

} // namespace tinlod::cli
