// Subcommand registry of the `tinlod` command line: each cmd_*.cpp registers itself, so commands
// live in their own files.
#pragma once

#include "tinlod/raster.hpp"
#include "tinlod/view.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tinlod::cli {

// Sets up a subcommand on `app`; returns the function run when it is chosen.
using Setup = std::function<std::function<void()>(CLI::App &app)>;

struct Command {
    std::string name;
    int order; // position in --help
    Setup setup;
};

std::vector<Command> &registry();

struct Register {
    Register(std::string name, int order, Setup setup) {
        registry().push_back({std::move(name), order, std::move(setup)});
    }
};

// Camera options shared by retrieve, simplify, render, compare, fly.
struct CameraOptions {
    std::string eye, at, viewport = "1920x1080";
    double fov = 60.0;
    void add(CLI::App &cmd, bool required);
    bool given() const { return !eye.empty() || !at.empty(); }
    View view() const; // validated; throws Error naming the option
};

// Raster loading options shared by the commands that read DEMs.
struct RasterOptions {
    std::optional<double> cell; // unset: 1 for rasters without georeferencing
    double zscale = 1.0;
    bool terrain_rgb = false;
    double max_memory_mb = 0; // --max-memory-mb; 0: this machine's physical memory
    // Peak memory of the command per raster sample, loading included (set by the command from a
    // measurement; see LoadOptions::bytes_per_sample).
    double bytes_per_sample = 0;
    void add(CLI::App &cmd);
    LoadOptions load_options() const;
};

} // namespace tinlod::cli
