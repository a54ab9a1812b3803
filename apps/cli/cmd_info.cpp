// `tinlod info INPUT [--json]`: what a raster or mesh holds, and its bounds in world units.
#include "commands.hpp"

#include "tinlod/mesh_io.hpp"
#include "tinlod/raster.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

namespace tinlod::cli {

static nlohmann::json raster_info(const std::string &path, const RasterOptions &ro) {
    const LoadOptions lo = ro.load_options();
    const Heightfield hf = load_heightfield(path, lo);
    const float lo_z = hf.min_z(), hi_z = hf.max_z();
    return {{"file", path},
            {"kind", "raster"},
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
            {"bounds", {0.0, 0.0, lo_z, (hf.width - 1) * hf.dx, (hf.height - 1) * hf.dy, hi_z}}};
}

static nlohmann::json mesh_info(const std::string &path) {
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
            {"bounds", {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]}}};
}

static Register info("info", 10, [](CLI::App &cmd) {
    cmd.description("Describe a DEM or mesh: size, values, voids, CRS, bounds in world units");
    struct Args {
        std::string input;
        bool json = false;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("INPUT", args->input,
                   "DEM (GeoTIFF, PNG, EXR, .hgt, ...) or mesh (PLY, OBJ, OFF, STL)")
        ->required();
    cmd.add_flag("--json", args->json, "print JSON instead of text");
    args->raster.add(cmd);
    return [args] {
        const nlohmann::json j = is_mesh_path(args->input) ? mesh_info(args->input)
                                                           : raster_info(args->input, args->raster);
        if (args->json) {
            std::cout << j.dump(2) << '\n';
            return;
        }
        for (const auto &[key, value] : j.items())
            std::cout << key << ": "
                      << (value.is_string() ? value.get<std::string>() : value.dump()) << '\n';
    };
});

} // namespace tinlod::cli
