// `tinlod`: view-dependent TINs from elevation rasters and meshes (see README.md).
#include "commands.hpp"

#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/util.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

namespace tinlod::cli {

std::vector<Command> &registry() {
    static std::vector<Command> commands;
    return commands;
}

void CameraOptions::add(CLI::App &cmd, bool required) {
    auto *e =
        cmd.add_option("--eye", eye, "observer position X,Y,Z (world units, see `tinlod info`)");
    auto *a = cmd.add_option("--at", at, "point the observer looks toward X,Y,Z");
    if (required) {
        e->required();
        a->required();
    }
    cmd.add_option("--fov", fov, "vertical field of view, degrees")->capture_default_str();
    cmd.add_option("--viewport", viewport, "viewport WxH, pixels")->capture_default_str();
}

View CameraOptions::view() const {
    View v;
    v.eye = parse_vec3(eye, "--eye");
    v.at = parse_vec3(at, "--at");
    v.fov_deg = fov;
    parse_viewport(viewport, v.viewport_w, v.viewport_h);
    validate(v, "--eye/--at");
    return v;
}

void RasterOptions::add(CLI::App &cmd) {
    cmd.add_option("--cell", cell,
                   "ground size of a pixel for rasters without georeferencing (default 1; an "
                   ".hgt file without an SRTM tile name needs it)");
    cmd.add_option("--zscale", zscale, "factor applied to every elevation")->capture_default_str();
    cmd.add_flag("--terrain-rgb", terrain_rgb,
                 "decode an RGB image as Mapbox Terrain-RGB: (R*65536+G*256+B)/10-10000");
    cmd.add_option("--max-memory-mb", max_memory_mb,
                   "refuse a DEM whose run would need more memory than this, MiB (default: this "
                   "machine's physical memory)")
        ->check(CLI::PositiveNumber);
}

// --threads N: a whole number from 1 to 1024, or 0 when the text is not one.
static int parse_threads(const std::string &text) {
    if (text.empty() || text.size() > 4 ||
        !std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); }))
        return 0;
    const int n = std::stoi(text);
    return n <= 1024 ? n : 0;
}

static void apply_threads(int n) {
    set_max_threads(n);
    // Mesa's software rasteriser (render, compare) sizes its own pool from this variable.
    ::setenv("LP_NUM_THREADS", std::to_string(n).c_str(), 1);
}

LoadOptions RasterOptions::load_options() const {
    LoadOptions lo;
    lo.cell = cell;
    lo.zscale = zscale;
    lo.terrain_rgb = terrain_rgb;
    lo.max_memory_mb = max_memory_mb;
    lo.bytes_per_sample = bytes_per_sample;
    return lo;
}

} // namespace tinlod::cli

int main(int argc, char **argv) {
    using namespace tinlod::cli;
    CLI::App app{
        "tinlod: view-dependent triangulated irregular networks from elevation rasters and "
        "meshes"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "tinlod 0.1.0");
    std::string threads;
    const CLI::Option *threads_option =
        app.add_option("--threads", threads,
                       "threads to run at once: loading, building, measuring, rendering (default: "
                       "every core)");
    // Options of the main command may also follow the subcommand's.
    app.fallthrough();
    auto &commands = registry();
    std::sort(commands.begin(), commands.end(),
              [](const Command &a, const Command &b) { return a.order < b.order; });
    std::vector<std::pair<CLI::App *, std::function<void()>>> runs;
    for (auto &c : commands) {
        CLI::App *sub = nullptr;
        runs.emplace_back(nullptr, nullptr);
        runs.back().second = c.setup(*(sub = app.add_subcommand(c.name, "")));
        runs.back().first = sub;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        return app.exit(e);
    }
    if (threads_option->count() > 0) {
        const int n = parse_threads(threads);
        if (n == 0) {
            std::fprintf(
                stderr,
                "tinlod: error: --threads: must be a whole number from 1 to 1024, not '%s'\n",
                threads.c_str());
            return 2; // a usage error, found before any work
        }
        apply_threads(n);
    }
    tinlod::install_interrupt_handlers();
    try {
        for (auto &[sub, run] : runs)
            if (sub->parsed())
                run();
    } catch (const tinlod::Interrupted &e) {
        std::fprintf(stderr, "tinlod: interrupted\n");
        return 128 + e.signal();
    } catch (const tinlod::Error &e) {
        std::fprintf(stderr, "tinlod: error: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "tinlod: error: out of memory\n");
        return 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "tinlod: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
