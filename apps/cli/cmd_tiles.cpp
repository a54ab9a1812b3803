// `tinlod tiles DEM... -o DIR [--min-zoom Z] [--max-zoom Z] [--normals] [--fill-height H]
// [--stats J] [--memory-mb M]`: a Cesium quantized-mesh-1.0 tile pyramid (lib/src/tiles,
// docs/tiles.md). `--plan`, `--part SPEC` and `--layer-only` cut the same build into jobs
// (python/tinlod_dask).
#include "commands.hpp"
#include "outputs.hpp"

#include "tinlod/error.hpp"
#include "tinlod/json_io.hpp"
#include "tinlod/tiles.hpp"
#include "tinlod/util.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace tinlod::cli {

// `--part`'s SPEC: Z/X/Y (that tile's subtree down to the last level) or top:Z (the levels from
// --min-zoom above Z), checked against the run's levels.
static PyramidPart parse_part(const std::string &spec, int first, int last) {
    PyramidPart part;
    char tail = 0;
    long long z = -1, x = -1, y = -1;
    if (std::sscanf(spec.c_str(), "top:%lld%c", &z, &tail) == 1) {
        if (z <= first || z > last + 1)
            throw UsageError("--part", spec + ": the cut must be a level from " +
                                           std::to_string(first + 1) + " to " +
                                           std::to_string(last + 1));
        part.top = true;
        part.root.z = int(z);
        return part;
    }
    if (std::sscanf(spec.c_str(), "%lld/%lld/%lld%c", &z, &x, &y, &tail) != 3 || z < first ||
        z > last || x < 0 || y < 0 || x >= (2LL << z) || y >= (1LL << z))
        throw UsageError("--part", spec + ": not Z/X/Y (a tile of levels " + std::to_string(first) +
                                       " to " + std::to_string(last) + ") or top:Z");
    part.root = {int(z), x, y};
    return part;
}

// `--plan`'s JSON: the run's levels, each with its tiles (layer.json's rectangles and their count),
// and the lattice's size and spacing, from which a driver cuts the build into --part jobs.
static nlohmann::json plan_json(const GeoLattice &lattice, const PyramidOptions &po,
                                const nlohmann::json &layer) {
    nlohmann::json levels = nlohmann::json::array();
    for (int z = po.min_zoom; z <= po.max_zoom; ++z) {
        const nlohmann::json &rects = layer["available"][std::size_t(z)];
        std::int64_t tiles = 0;
        for (const auto &r : rects)
            tiles += (r["endX"].get<std::int64_t>() - r["startX"].get<std::int64_t>() + 1) *
                     (r["endY"].get<std::int64_t>() - r["startY"].get<std::int64_t>() + 1);
        levels.push_back({{"z", z}, {"tiles", tiles}, {"available", rects}});
    }
    return {{"min_zoom", po.min_zoom},
            {"max_zoom", po.max_zoom},
            {"lattice",
             {{"width", lattice.width},
              {"height", lattice.height},
              {"spacing_deg", {lattice.dlon, lattice.dlat}}}},
            {"levels", levels}};
}

static Register tiles("tiles", 75, [](CLI::App &cmd) {
    cmd.description(
        "Write a Cesium quantized-mesh-1.0 terrain tile pyramid (geographic TMS, gzip, "
        "layer.json): each tile within CesiumJS's geometric error for its level at every DEM "
        "sample, and neighbours sharing their edges vertex for vertex");
    struct Args {
        std::vector<std::string> inputs;
        std::string output, stats, part;
        int min_zoom = 0, max_zoom = 0;
        double fill_height = 0.0;
        double memory_mb = 0.0;
        bool normals = false, plan = false, layer_only = false;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("DEM", args->inputs,
                   "georeferenced DEM files, one coverage (adjacent SRTM tiles, say); any CRS")
        ->required();
    cmd.add_option("-o,--output", args->output, "folder of the tile set (created when missing)")
        ->required();
    cmd.add_option("--stats", args->stats, "write statistics as JSON");
    auto *min_zoom = cmd.add_option("--min-zoom", args->min_zoom, "first level written")
                         ->check(whole_in(0, k_max_tile_level))
                         ->capture_default_str();
    auto *max_zoom =
        cmd.add_option("--max-zoom", args->max_zoom,
                       "last level written (default: the first whose tiles are at most 64 DEM "
                       "spacings across, the DEM's resolution for CesiumJS's error estimate)")
            ->check(whole_in(0, k_max_tile_level));
    cmd.add_option("--fill-height", args->fill_height,
                   "height outside the DEMs in partly covered tiles, metres above the ellipsoid")
        ->check(real_in(-12000.0, 12000.0))
        ->capture_default_str();
    cmd.add_option("--memory-mb", args->memory_mb,
                   "memory the run may hold, MiB: past it the DEMs are read by windows "
                   "(default: half of this machine's memory)")
        ->check(real_in(1.0, 1e9));
    cmd.add_flag("--normals", args->normals,
                 "add the oct-encoded vertex normals extension (normals of the DEM)");
    auto *part =
        cmd.add_option("--part", args->part,
                       "build only Z/X/Y's subtree (levels Z to --max-zoom) or top:Z (the levels "
                       "above Z), writing each tile into DIR in place and no layer.json: the jobs "
                       "of a build spread over processes (python/tinlod_dask)");
    auto *layer_only = cmd.add_flag("--layer-only", args->layer_only,
                                    "write only DIR/layer.json (after the --part jobs)");
    auto *plan = cmd.add_flag("--plan", args->plan,
                              "print the levels and their tiles (layer.json's `available`) as "
                              "JSON and write nothing");
    part->excludes(layer_only)->excludes(plan);
    layer_only->excludes(plan);
    for (auto *o : {layer_only, plan})
        o->excludes("--stats");
    args->raster.add(cmd);
    declare_outputs(cmd, {{"--output", &args->output}, {"--stats", &args->stats}},
                    "The tile set is staged inside DIR and its levels moved in at the end: a "
                    "failed run leaves DIR as it was. Serve the .terrain files with "
                    "`Content-Encoding: gzip` (docs/tiles.md).");
    return [args, min_zoom, max_zoom] {
        args->raster.refuse_max_memory("tiles");
        (void)min_zoom;
        if (max_zoom->count() > 0 && args->min_zoom > args->max_zoom)
            throw UsageError("--min-zoom", "is past --max-zoom");
        for (const std::string &path : args->inputs)
            if (is_store_path(path))
                throw UsageError(path, "is a store: tiles need the DEM file, georeferenced");
        if (!args->plan) {
            check_writable_folder(args->output);
            check_writable({args->stats});
        }
        StageTimes times;
        CoverageMemory memory;
        memory.memory_mb = args->memory_mb > 0 ? args->memory_mb : default_memory_mb();
        memory.threads = max_threads();
        const GeoLattice lattice = load_coverage(args->inputs, args->raster.load_options(), memory);
        times.lap("load");
        const int finest = finest_zoom(lattice);
        const int last = max_zoom->count() > 0 ? args->max_zoom : default_max_zoom(lattice);
        if (last > finest)
            throw UsageError("--max-zoom", "level " + std::to_string(last) +
                                               " has tiles narrower than 4 DEM spacings: the "
                                               "DEMs reach level " +
                                               std::to_string(finest));
        if (args->min_zoom > last)
            throw UsageError("--min-zoom", "is past the last level, " + std::to_string(last));
        PyramidOptions po;
        po.min_zoom = args->min_zoom;
        po.max_zoom = last;
        po.tile.fill_height = args->fill_height;
        po.tile.normals = args->normals;
        po.threads = max_threads();
        if (args->plan || args->layer_only) {
            const nlohmann::json layer = pyramid_layer(lattice, po);
            if (args->layer_only) {
                std::filesystem::create_directories(args->output);
                write_atomically((std::filesystem::path(args->output) / "layer.json").string(),
                                 [&](const std::string &path) { write_layer(layer, path); });
                return;
            }
            std::cout << plan_json(lattice, po, layer).dump() << '\n';
            return;
        }
        std::unique_ptr<Progress> bar;
        po.progress = [&bar](std::int64_t done, std::int64_t total) {
            if (!bar)
                bar = std::make_unique<Progress>("tiles", total);
            bar->update(done);
        };
        const PyramidStats ps =
            args->part.empty()
                ? write_pyramid(lattice, args->output, po)
                : write_pyramid_part(lattice, args->output, po,
                                     parse_part(args->part, po.min_zoom, po.max_zoom));
        if (bar)
            bar->finish();
        times.lap("tiles");

        std::int64_t tiles = 0, triangles = 0, vertices = 0, bytes = 0, over_bound = 0;
        std::int64_t repaired = 0, repaired_posts = 0;
        double worst = 0.0, max_error = 0.0;
        TileId worst_tile;
        nlohmann::json levels = nlohmann::json::array();
        for (const LevelStats &l : ps.levels) {
            tiles += l.tiles, triangles += l.triangles, vertices += l.vertices, bytes += l.bytes;
            over_bound += l.over_bound;
            repaired += l.repaired, repaired_posts += l.repaired_posts;
            if (l.worst_ratio > worst)
                worst = l.worst_ratio, worst_tile = l.worst_tile;
            max_error = std::max(max_error, l.max_error);
            levels.push_back({{"z", l.z},
                              {"tiles", l.tiles},
                              {"triangles", l.triangles},
                              {"vertices", l.vertices},
                              {"bytes", l.bytes},
                              {"bound_m", l.bound},
                              {"max_error_m", l.max_error},
                              {"worst_ratio", l.worst_ratio},
                              {"over_bound", l.over_bound},
                              {"rebuilt", l.rebuilt},
                              {"repaired", l.repaired},
                              {"repaired_posts", l.repaired_posts},
                              {"bands_read", l.bands_read}});
        }
        if (!args->stats.empty())
            write_json(args->stats,
                       {{"input",
                         {{"files", args->inputs},
                          {"nodes", std::int64_t(lattice.width) * lattice.height},
                          {"triangles", 2 * std::int64_t(lattice.width - 1) * (lattice.height - 1)},
                          {"covered", lattice.covered},
                          {"resampled", lattice.resampled},
                          // By windows: the lattice's bands, and those made from the DEMs in
                          // all (a band made again after its eviction counts again).
                          {"bands", lattice.band_count()},
                          {"bands_read", lattice.bands_read()},
                          {"spacing_deg", {lattice.dlon, lattice.dlat}}}},
                        {"output",
                         {{"dir", args->output},
                          {"tiles", tiles},
                          {"nodes", vertices},
                          {"triangles", triangles},
                          {"bytes", bytes},
                          {"min_zoom", args->min_zoom},
                          {"max_zoom", last}}},
                        {"levels", levels},
                        // max_error_m: the larger of the vertical error and the distance to the
                        // triangles as CesiumJS draws them (docs/tiles.md), so not max_vertical.
                        {"error",
                         {{"worst_ratio", worst},
                          {"max_error_m", max_error},
                          {"tiles_over_bound", over_bound},
                          {"tiles_repaired", repaired},
                          {"posts_repaired", repaired_posts},
                          {"max_screen_px", nullptr}}},
                        {"time_ms", times.json()},
                        {"tiles_per_s", double(tiles) / (ps.ms / 1000.0)},
                        {"threads", max_threads()},
                        {"peak_rss_mb", peak_rss_mb()}});
        std::printf("%s: %lld tiles on levels %d to %d, %lld triangles, %.1f MB in %s; worst "
                    "error %.3g of the level's bound\n",
                    args->output.c_str(), static_cast<long long>(tiles),
                    ps.levels.empty() ? po.min_zoom : ps.levels.front().z,
                    ps.levels.empty() ? last : ps.levels.back().z,
                    static_cast<long long>(triangles), double(bytes) / 1e6, times.summary().c_str(),
                    worst);
        // The build's rebuilds did not bring every tile within its bound: said, never silent.
        if (over_bound > 0)
            std::fprintf(stderr,
                         "tinlod: warning: %s: %lld tiles over their level's error after every "
                         "rebuild, the worst %d/%lld/%lld at %.3g of it (docs/tiles.md)\n",
                         args->output.c_str(), static_cast<long long>(over_bound), worst_tile.z,
                         static_cast<long long>(worst_tile.x), static_cast<long long>(worst_tile.y),
                         worst);
    };
});

} // namespace tinlod::cli
