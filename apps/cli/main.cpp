// `tinlod`: view-dependent TINs from elevation rasters and meshes (see README.md).
#include "commands.hpp"

#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/util.hpp"
#include "tinlod/version.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

namespace tinlod::cli {

std::vector<Command> &registry() {
    static std::vector<Command> commands;
    return commands;
}

static std::string shown(const std::string &text) { return "'" + text + "'"; }

CLI::Validator real_in(double lo, double hi, bool open_lo, bool open_hi) {
    char range[96] = "";
    if (std::isinf(hi) && !std::isinf(lo))
        std::snprintf(range, sizeof range, " %s %g", open_lo ? ">" : ">=", lo);
    else if (!std::isinf(hi))
        std::snprintf(range, sizeof range, " in %c%g, %g%c", open_lo ? '(' : '[', lo, hi,
                      open_hi ? ')' : ']');
    const std::string wanted = std::string("must be a finite number") + range;
    return CLI::Validator(
        [=](std::string &text) -> std::string {
            char *end = nullptr;
            errno = 0;
            const double x = std::strtod(text.c_str(), &end);
            const bool number = !text.empty() && *end == '\0' && errno != ERANGE &&
                                !std::isspace(static_cast<unsigned char>(text[0]));
            const bool inside = (open_lo ? x > lo : x >= lo) && (open_hi ? x < hi : x <= hi);
            return number && std::isfinite(x) && inside ? std::string()
                                                        : wanted + ", not " + shown(text);
        },
        std::string("NUMBER") + range);
}

CLI::Validator whole_in(std::int64_t lo, std::int64_t hi) {
    const std::string range = "from " + std::to_string(lo) + " to " + std::to_string(hi);
    return CLI::Validator(
        [=](std::string &text) -> std::string {
            char *end = nullptr;
            errno = 0;
            const long long x = std::strtoll(text.c_str(), &end, 10);
            const bool number = !text.empty() && *end == '\0' && errno != ERANGE &&
                                !std::isspace(static_cast<unsigned char>(text[0]));
            return number && x >= lo && x <= hi
                       ? std::string()
                       : "must be a whole number " + range + ", not " + shown(text);
        },
        "INTEGER " + range);
}

// A check that runs one of the library's parsers on the option's text; its Error becomes CLI11's
// usage error.
template <class Parse> static CLI::Validator parsed_by(Parse parse, const std::string &what) {
    return CLI::Validator(
        [parse](std::string &text) -> std::string {
            try {
                parse(text);
                return {};
            } catch (const Error &e) {
                return e.reason();
            }
        },
        what);
}

CLI::Validator viewport_text() {
    return parsed_by(
        [](const std::string &text) {
            int w = 0, h = 0;
            parse_viewport(text, w, h);
        },
        "WxH");
}

CLI::Validator point_text() {
    return parsed_by([](const std::string &text) { parse_vec3(text, ""); }, "X,Y,Z");
}

void CameraOptions::add(CLI::App &cmd, bool required) {
    const auto point = point_text();
    auto *e =
        cmd.add_option("--eye", eye, "observer position X,Y,Z (world units, see `tinlod info`)")
            ->check(point);
    auto *a = cmd.add_option("--at", at, "point the observer looks toward X,Y,Z")->check(point);
    if (required) {
        e->required();
        a->required();
    }
    cmd.add_option("--fov", fov, "vertical field of view, degrees")
        ->check(real_in(0.0, 180.0, true, true))
        ->capture_default_str();
    cmd.add_option("--viewport", viewport, "viewport WxH, pixels (each side 1 to 65536)")
        ->check(viewport_text())
        ->capture_default_str();
}

View CameraOptions::view() const {
    // The texts passed their checks when parsed: what is left to refuse is the pair of points.
    View v;
    v.eye = parse_vec3(eye, "--eye");
    v.at = parse_vec3(at, "--at");
    v.fov_deg = fov;
    parse_viewport(viewport, v.viewport_w, v.viewport_h);
    try {
        validate(v, "--eye/--at");
    } catch (const Error &e) {
        throw UsageError(e.subject(), e.reason());
    }
    return v;
}

void RasterOptions::add(CLI::App &cmd) {
    given_.push_back(cmd.add_option("--cell", cell,
                                    "ground size of a pixel for rasters without georeferencing "
                                    "(default 1; an .hgt file without an SRTM tile name needs it)")
                         ->check(real_in(0.0, INFINITY, true)));
    // Zero would flatten the terrain to nothing: refused like the library's loader does.
    given_.push_back(cmd.add_option("--zscale", zscale, "factor applied to every elevation (not 0)")
                         ->check(real_in(-INFINITY, INFINITY) &
                                 CLI::Validator(
                                     [](std::string &text) -> std::string {
                                         return std::strtod(text.c_str(), nullptr) == 0.0
                                                    ? "must not be 0"
                                                    : "";
                                     },
                                     "not 0"))
                         ->capture_default_str());
    given_.push_back(
        cmd.add_flag("--terrain-rgb", terrain_rgb,
                     "decode an RGB image as Mapbox Terrain-RGB: (R*65536+G*256+B)/10-10000"));
    cmd.add_option("--max-memory-mb", max_memory_mb,
                   "refuse a DEM whose run would need more memory than this, MiB (default: this "
                   "machine's physical memory)")
        ->check(real_in(0.0, INFINITY, true));
}

double StageTimes::total() const {
    double sum = 0.0;
    for (const auto &stage : stages)
        sum += stage.second;
    return sum;
}

nlohmann::json StageTimes::json() const {
    nlohmann::json j = nlohmann::json::object();
    for (const auto &[name, ms] : stages)
        j[name] = ms;
    return j;
}

std::string StageTimes::summary() const {
    char part[96];
    std::snprintf(part, sizeof part, "%.0f ms (", total());
    std::string text = part;
    for (std::size_t i = 0; i < stages.size(); ++i) {
        std::snprintf(part, sizeof part, "%s%s %.0f", i > 0 ? ", " : "", stages[i].first.c_str(),
                      stages[i].second);
        text += part;
    }
    return text + ")";
}

bool is_store_path(const std::string &path) {
    return is_store_file(path) || std::filesystem::path(path).extension() == ".tlq";
}

void RasterOptions::check_store(const std::string &path) const {
    for (const CLI::Option *o : given_)
        if (o->count() > 0)
            throw UsageError(o->get_name(), path + " is a store: it keeps the cell size and "
                                                   "heights it was built with");
}

Heightfield RasterOptions::load(const std::string &path) const {
    if (!is_store_path(path))
        return load_heightfield(path, load_options());
    check_store(path);
    return TileStore(path).heightfield();
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
    // Past a file-size limit (ulimit -f) a write then fails with EFBIG ("File too large"), reported
    // as any failed write, its temporary removed, instead of SIGXFSZ killing the process silently.
    std::signal(SIGXFSZ, SIG_IGN);
    using namespace tinlod::cli;
    CLI::App app{
        "tinlod: view-dependent triangulated irregular networks from elevation rasters and "
        "meshes"};
    app.require_subcommand(1);
    app.set_version_flag("--version", tinlod::version_line("tinlod"));
    app.footer(
        "Exit status: 0 done; 1 bad input or failed work, 2 a usage error (a wrong option or "
        "value, found before any work); either prints one line on stderr, "
        "`tinlod: error: FILE or OPTION: problem`.");
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
    // Exit status: 0 done (--help and --version print to stdout), 1 bad input or failed work,
    // 2 a usage error; every error is one line on stderr, `tinlod: error: ...`.
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp &e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp &e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion &e) {
        return app.exit(e);
    } catch (const CLI::ParseError &e) {
        std::string help = "tinlod";
        for (const auto &[sub, run] : runs)
            if (sub->parsed())
                help += " " + sub->get_name();
        std::fprintf(stderr, "tinlod: error: %s (see `%s --help`)\n", e.what(), help.c_str());
        return 2;
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
    } catch (const UsageError &e) {
        std::fprintf(stderr, "tinlod: error: %s\n", e.what());
        return 2;
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
