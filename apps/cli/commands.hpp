// Subcommand registry of the `tinlod` command line: each cmd_*.cpp registers itself, so commands
// live in their own files.
#pragma once

#include "tinlod/error.hpp"
#include "tinlod/json_io.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/util.hpp"
#include "tinlod/view.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
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

// The command line itself is wrong: an option's value, a missing or conflicting option. main()
// prints it as any Error but exits 2, as for CLI11's parse errors; bad input and failed work
// exit 1.
class UsageError : public Error {
  public:
    using Error::Error;
};

// Checks of an option's text, run by CLI11 as it parses (a failure is a usage error naming the
// option): the whole text is one finite number in the range (empty, nan, inf, an overflow or
// trailing characters fail). `open_lo`/`open_hi` leave that end out of the range.
CLI::Validator real_in(double lo, double hi, bool open_lo = false, bool open_hi = false);
// The whole text is a whole number in [lo, hi] (no sign, fraction or exponent past it).
CLI::Validator whole_in(std::int64_t lo, std::int64_t hi);

// The text is a point X,Y,Z of finite numbers (parse_vec3), or a viewport WxH (parse_viewport).
CLI::Validator point_text();
CLI::Validator viewport_text();

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
    // The DEM file, or the quad-tree store (`tinlod build`) at `path`, whole. A store keeps the
    // cell size and heights it was built with: --cell, --zscale or --terrain-rgb given with one is
    // a usage error.
    Heightfield load(const std::string &path) const;
    // Throws that usage error when one of them was given for the store at `path`.
    void check_store(const std::string &path) const;
    // A command that reads a DEM by windows past --memory-mb (tiles, build) takes no
    // --max-memory-mb: a usage error naming --memory-mb when it was given.
    void refuse_max_memory(const std::string &command) const;

  private:
    std::vector<const CLI::Option *> given_; // the options above, to tell whether one was given
    const CLI::Option *max_memory_ = nullptr;
};

// The stages a command ran, in order, with their wall times: the stats' time_ms and the summary's
// "T ms (start a, load b, ...)" come from one list, and each lap() closes the stage begun where the
// last one ended, so the parts add up to the whole run. The first stage, "start", runs from the
// process's start (loading the program and its libraries, parsing the command line) to the list's
// construction.
class StageTimes {
  public:
    StageTimes();
    // Ends the running stage as `name`: the time since the last lap, less what add() took from it.
    // Returns that time.
    double lap(const std::string &name);
    // A part of the running stage timed elsewhere (e.g. inside the library), as its own stage.
    void add(const std::string &name, double ms);
    // Renames a stage (the first stage of a DEM is named by what it was).
    void rename(const std::string &from, const std::string &to);
    double total() const;        // from the process's start to the last lap
    nlohmann::json json() const; // {"start": a, "load": b, ..., "total": T}
    std::string summary() const; // "T ms (start a, load b, ...)"

  private:
    std::vector<std::pair<std::string, double>> stages_;
    Stopwatch clock_;       // since the last lap
    double started_ms_;     // the process's age when the list was made
    double laps_ms_ = 0.0;  // the stages lap() closed, the "start" one included
    double added_ms_ = 0.0; // what add() took from the running stage
};

// Whether `path` names a quad-tree store: its magic bytes, or a .tlq name (whose store errors then
// say what is wrong with it).
bool is_store_path(const std::string &path);

} // namespace tinlod::cli
