// `tinlod-view [DEM|STORE|MESH]`: the interactive viewer, and its scripted mode
// `tinlod-view INPUT --script PATH.csv --screenshot OUT.png [--frames N] [--size WxH] [--stats
// CSV]` for tests and demos; DEMs take the command line's --cell, --zscale and --terrain-rgb.
// Errors print one line on stderr and exit non-zero.
#include "commands.hpp"
#include "viewer.hpp"

#include "tinlod/error.hpp"
#include "tinlod/version.hpp"
#include "tinlod/view.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <exception>
#include <map>

int main(int argc, char **argv) {
    // Past a file-size limit (ulimit -f) a write then fails with EFBIG ("File too large"), reported
    // as any failed write, its temporary removed, instead of SIGXFSZ killing the process silently.
    std::signal(SIGXFSZ, SIG_IGN);
    using namespace tinlod;
    using namespace tinlod::viewer;
    CLI::App app{"tinlod-view: fly over a terrain and watch its level of detail follow you"};
    app.set_version_flag("--version", version_line("tinlod-view"));
    ViewerOptions options;
    std::string size = "1280x720", color = "height";
    bool erase = false, refine = false, no_cull = false;
    app.add_option("INPUT", options.input,
                   "DEM, quad-tree store (.tlq) or mesh (.ply .obj .off .stl)");
    app.add_option("--script", options.script,
                   "play this camera path (t,eye_x,eye_y,eye_z,at_x,at_y,at_z) without user input, "
                   "then exit");
    app.add_option("--screenshot", options.screenshot, "scripted mode: PNG of the last frame");
    app.add_option("--frames", options.frames,
                   "scripted mode: frames evenly spaced over the path (default: one per keyframe)");
    app.add_option("--stats", options.stats,
                   "scripted mode: per-frame CSV (t, nodes, triangles, ms)");
    app.add_option("--size", size, "window size WxH, pixels")->capture_default_str();
    app.add_option("--fov", options.fov_deg, "vertical field of view, degrees")
        ->capture_default_str();
    app.add_option("--tol", options.lod.tol_px, "screen-space error bound tau, pixels")
        ->capture_default_str();
    app.add_flag("--erase", erase, "erase nodes by significance after retrieval");
    app.add_flag("--refine", refine,
                 "DEM/store: keep one TIN between frames, erasing and recovering nodes");
    app.add_flag("--no-cull", no_cull, "keep the bound outside the view frustum too");
    app.add_option("--color", color, "shade, height, sp, level or error")->capture_default_str();
    app.add_flag("--wire", options.wire, "wireframe overlay");
    app.add_flag("--ui", options.ui, "scripted mode: draw the panel into the screenshot");
    cli::RasterOptions raster;
    raster.add(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        if (e.get_exit_code() == 0) // --help, --version
            return app.exit(e);
        std::fprintf(stderr, "tinlod-view: %s\n", e.what());
        return 2; // a usage error, as the command line's
    }
    options.load = raster.load_options();

    try {
        parse_viewport(size, options.width, options.height);
        if (!(options.lod.tol_px >= 0.0 && std::isfinite(options.lod.tol_px)))
            throw Error("--tol", "must be a finite number of pixels >= 0");
        if (!(options.fov_deg > 0.0 && options.fov_deg < 180.0))
            throw Error("--fov", "must lie strictly between 0 and 180 degrees");
        const std::map<std::string, ColorBy> colors = {{"shade", ColorBy::shade},
                                                       {"height", ColorBy::height},
                                                       {"sp", ColorBy::sp},
                                                       {"level", ColorBy::level},
                                                       {"error", ColorBy::error}};
        const auto c = colors.find(color);
        if (c == colors.end())
            throw Error("--color", "unknown colouring '" + color + "'");
        options.lod.color = c->second;
        options.lod.stages = refine  ? LodStages::refine
                             : erase ? LodStages::retrieve_erase
                                     : LodStages::retrieve;
        options.lod.cull = !no_cull;
        if (!options.script.empty()) {
            if (options.input.empty())
                throw Error("--script", "needs an INPUT file");
            if (options.screenshot.empty())
                throw Error("--script", "needs --screenshot OUT.png");
            if (options.frames < 0)
                throw Error("--frames", "must be >= 0");
        } else if (!options.screenshot.empty() || !options.stats.empty()) {
            throw Error("--screenshot", "--screenshot and --stats need --script");
        }
        if (cli::is_store_path(options.input))
            raster.check_store(options.input);
        run_viewer(options);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "tinlod-view: %s\n", e.what());
        return 1;
    }
    return 0;
}
