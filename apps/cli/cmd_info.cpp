// `tinlod info INPUT [--json]`: what a raster, store or mesh holds, and its bounds in world units.
#include "commands.hpp"

#include "tinlod/mesh_io.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

namespace tinlod::cli {

// In the order a reader asks: what it is, its size, its values, where it lies.
using Json = nlohmann::ordered_json;

static Json bounds(double x0, double y0, double z0, double x1, double y1, double z1) {
    return Json::array({x0, y0, z0, x1, y1, z1});
}

static Json raster_info(const std::string &path, const RasterOptions &ro) {
    const Heightfield hf = ro.load(path);
    const float lo_z = hf.min_z(), hi_z = hf.max_z();
    Json j = {
        {"file", path},
        {"kind", is_store_path(path) ? "store" : "raster"},
        {"width", hf.width},
        {"height", hf.height},
        {"min", lo_z},
        {"max", hi_z},
        {"voids", hf.voids},
        {"voids_filled", hf.filled},
        {"cropped_samples", hf.cropped},
        {"crs", hf.crs},
        {"cell_size", {hf.dx, hf.dy}},
        {"origin", {hf.origin_x, hf.origin_y}},
        {"bounds", bounds(0.0, 0.0, lo_z, (hf.width - 1) * hf.dx, (hf.height - 1) * hf.dy, hi_z)}};
    if (is_store_path(path)) {
        const TileStore store(path);
        j["tiles"] = store.tile_count();
        j["tile_level"] = store.tile_level();
        j["bytes"] = store.file_bytes();
    }
    return j;
}

static Json mesh_info(const std::string &path) {
    MeshReport report;
    const Mesh mesh = read_mesh(path, &report);
    Mesh::Point lo(1e30f), hi(-1e30f);
    for (auto v : mesh.vertices()) {
        lo.minimize(mesh.point(v));
        hi.maximize(mesh.point(v));
    }
    return {{"file", path},
            {"kind", "mesh"},
            {"vertices", report.vertices},
            {"faces", report.faces},
            {"boundary_edges", report.boundary_edges},
            {"non_manifold_edges", report.non_manifold_edges},
            {"duplicated_vertices", report.duplicated_vertices},
            {"isolated_vertices", report.isolated_vertices},
            {"bounds", bounds(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2])}};
}

// A value on one line of text: arrays of numbers by name where the names are known.
static std::string text(const std::string &key, const Json &value) {
    static const char *const k_bounds[] = {"xmin", "ymin", "zmin", "xmax", "ymax", "zmax"};
    static const char *const k_xy[] = {"x", "y"};
    const char *const *names = key == "bounds"                         ? k_bounds
                               : key == "cell_size" || key == "origin" ? k_xy
                                                                       : nullptr;
    if (value.is_string())
        return value.get<std::string>();
    if (!names || !value.is_array())
        return value.dump();
    std::string out;
    for (std::size_t i = 0; i < value.size(); ++i)
        out += (i > 0 ? " " : "") + std::string(names[i]) + " " + value[i].dump();
    return out;
}

static Register info("info", 10, [](CLI::App &cmd) {
    cmd.description(
        "Describe a DEM, store or mesh: size, values, voids, CRS, bounds in world units (a "
        "store also its tiles and bytes)");
    struct Args {
        std::string input;
        bool json = false;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("INPUT", args->input,
                   "DEM (GeoTIFF, PNG, EXR, .hgt, ...), quad-tree store (.tlq) or mesh (PLY, OBJ, "
                   "OFF, STL)")
        ->required();
    cmd.add_flag("--json", args->json, "print JSON instead of text");
    args->raster.add(cmd);
    return [args] {
        const Json j = is_mesh_path(args->input) ? mesh_info(args->input)
                                                 : raster_info(args->input, args->raster);
        if (args->json) {
            std::cout << j.dump(2) << '\n';
            return;
        }
        for (const auto &[key, value] : j.items())
            std::cout << key << ": " << text(key, value) << '\n';
    };
});

} // namespace tinlod::cli
