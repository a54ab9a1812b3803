// The options the commands share (camera, raster loading) and their validators. tinlod-view
// compiles this file too, so both programs have one definition of --cell, --zscale and
// --terrain-rgb, their help and their checks.
#include "commands.hpp"

#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace tinlod::cli {

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
    max_memory_ = cmd.add_option("--max-memory-mb", max_memory_mb,
                                 "refuse a DEM whose run would need more memory than this, MiB "
                                 "(default: this machine's physical memory; not with --memory-mb's "
                                 "commands, tiles and build)")
                      ->check(real_in(0.0, INFINITY, true));
}

void RasterOptions::refuse_max_memory(const std::string &command) const {
    if (max_memory_ && max_memory_->count() > 0)
        throw UsageError("--max-memory-mb",
                         command + " reads a DEM larger than its memory by windows: bound it with "
                                   "--memory-mb");
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
