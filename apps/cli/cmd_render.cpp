// `tinlod render MESH|DEM --eye ... --at ... -o IMAGE.png [--color ...] [--wire] [--depth D.exr]`:
// a picture of a TIN or mesh through the headless OpenGL renderer.
//
// The colourings that need per-node or per-face values compute them here, simply, until the
// library's own significance and erase levels are wired in:
//   sp     how far the node stands out of its neighbours: its offset from their centroid along
//          its normal, in screen pixels (d * k / OD);
//   level  the quad-tree depth at which the node's grid sample first appears (0 = the corners of
//          the whole grid, log2(size - 1) = the finest samples);
//   error  per face, the largest vertical distance between the face and the DEM samples under it.
// Each of these renders carries a legend: the colour bar from 0 to the top of the map, with units.
#include "commands.hpp"
#include "outputs.hpp"

#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/render.hpp"
#include "tinlod/util.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

namespace tinlod::cli {

namespace {

// Node deviation from its one-ring centroid along the node's normal (so the sideways offset of a
// boundary node's ring does not count), in pixels as seen from the eye.
std::vector<float> node_screen_deviation(const Mesh &mesh, const View &view) {
    std::vector<float> sp(mesh.n_vertices(), 0.0f);
    const auto at = [&](Mesh::VertexHandle v) {
        const auto &q = mesh.point(v);
        return glm::dvec3(q[0], q[1], q[2]);
    };
    for (auto v : mesh.vertices()) {
        glm::dvec3 sum(0.0), normal(0.0);
        int n = 0;
        for (auto u : v.vertices()) {
            sum += at(u);
            ++n;
        }
        for (auto f : v.faces()) {
            glm::dvec3 p[3];
            int i = 0;
            for (auto w : f.vertices())
                p[i++] = at(w);
            normal += glm::cross(p[1] - p[0], p[2] - p[0]);
        }
        if (n == 0 || glm::length(normal) == 0.0)
            continue;
        const glm::dvec3 here = at(v);
        const double deviation = std::abs(glm::dot(here - sum / double(n), glm::normalize(normal)));
        sp[v.idx()] = float(view.screen_px(deviation, here));
    }
    return sp;
}

// Grid column and row of the sample a node stands on; throws when it is off the grid.
std::pair<int, int> grid_cell(const Heightfield &hf, const Mesh::Point &p) {
    const double c = p[0] / hf.dx, r = p[1] / hf.dy;
    const double ci = std::round(c), ri = std::round(r);
    if (std::abs(c - ci) > 1e-3 || std::abs(r - ri) > 1e-3 || ci < 0 || ri < 0 || ci >= hf.width ||
        ri >= hf.height)
        throw Error("--color level", "a node is not on a sample of the DEM grid");
    return {int(ci), int(ri)};
}

std::vector<float> node_levels(const Mesh &mesh, const Heightfield &hf, int &deepest) {
    deepest = int(std::bit_width(unsigned(std::max(hf.width, hf.height) - 2)));
    std::vector<float> level(mesh.n_vertices(), 0.0f);
    for (auto v : mesh.vertices()) {
        const auto [c, r] = grid_cell(hf, mesh.point(v));
        const int zeros = std::min({c == 0 ? deepest : std::countr_zero(unsigned(c)),
                                    r == 0 ? deepest : std::countr_zero(unsigned(r)), deepest});
        level[v.idx()] = float(deepest - zeros);
    }
    return level;
}

// Largest |z_sample - z_face| over the DEM samples whose xy falls inside each face.
std::vector<float> face_vertical_error(const Mesh &mesh, const Heightfield &hf) {
    std::vector<float> error(mesh.n_faces(), 0.0f);
    for (auto f : mesh.faces()) {
        if (mesh.status(f).deleted())
            continue;
        auto p = face_corners(mesh, f);
        for (auto &q : p)
            q = glm::dvec3(q.x / hf.dx, q.y / hf.dy, q.z); // grid units
        const double area =
            (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
        if (area == 0.0)
            continue;
        const int c0 = std::max(0, int(std::ceil(std::min({p[0].x, p[1].x, p[2].x}) - 1e-6)));
        const int c1 =
            std::min(hf.width - 1, int(std::floor(std::max({p[0].x, p[1].x, p[2].x}) + 1e-6)));
        const int r0 = std::max(0, int(std::ceil(std::min({p[0].y, p[1].y, p[2].y}) - 1e-6)));
        const int r1 =
            std::min(hf.height - 1, int(std::floor(std::max({p[0].y, p[1].y, p[2].y}) + 1e-6)));
        double worst = 0.0;
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c) {
                const double w0 =
                    ((p[1].x - c) * (p[2].y - r) - (p[2].x - c) * (p[1].y - r)) / area;
                const double w1 =
                    ((p[2].x - c) * (p[0].y - r) - (p[0].x - c) * (p[2].y - r)) / area;
                const double w2 = 1.0 - w0 - w1;
                if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9)
                    continue;
                const double z = w0 * p[0].z + w1 * p[1].z + w2 * p[2].z;
                worst = std::max(worst, std::abs(double(hf.at(c, r)) - z));
            }
        error[f.idx()] = float(worst);
    }
    return error;
}

} // namespace

static Register render("render", 60, [](CLI::App &cmd) {
    cmd.description("Render a TIN, mesh or DEM to an image (headless OpenGL 3.3)");
    struct Args {
        std::string input, output, color = "shade", depth, reference;
        bool wire = false, dem_normals = false;
        float scalar_max = 0.0f;
        CameraOptions camera;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("INPUT", args->input,
                   "mesh (PLY, OBJ, OFF, STL), or DEM or store (.tlq) drawn as its full grid TIN")
        ->required();
    cmd.add_option("-o,--output", args->output, "image (.png, .tif, .exr, ...)")->required();
    cmd.add_option("--color", args->color, "shade | height | sp | level | error")
        ->check(CLI::IsMember({"shade", "height", "sp", "level", "error"}))
        ->capture_default_str();
    cmd.add_flag("--wire", args->wire, "overlay the triangle edges");
    cmd.add_option("--depth", args->depth, "also write depth along the view axis (.exr)");
    declare_outputs(cmd, {{"--output", &args->output}, {"--depth", &args->depth}});
    cmd.add_option("--reference", args->reference,
                   "the DEM or store the mesh was made from (for --color error and level)");
    cmd.add_flag("--dem-normals", args->dem_normals,
                 "shade with the DEM's own normals (the input or --reference DEM) instead of the "
                 "mesh's");
    cmd.add_option("--scalar-max", args->scalar_max,
                   "value at the top of the colour map for sp/level/error (default: the largest; "
                   "for sp the 99th percentile)")
        ->check(real_in(0.0, INFINITY));
    args->camera.add(cmd, true);
    args->raster.add(cmd);
    // Peak memory per DEM sample of `tinlod render`, measured
    // (docs/decisions/memory-per-sample.md).
    args->raster.bytes_per_sample = 380;
    return [args] {
        Stopwatch clock;
        const View view = args->camera.view();
        check_writable({args->output, args->depth});
        const bool has_dem = !is_mesh_path(args->input) || !args->reference.empty();
        if ((args->color == "level" || args->color == "error") && !has_dem)
            throw UsageError("--color " + args->color,
                             "needs the DEM: give a DEM or --reference DEM");
        if (args->dem_normals && !has_dem)
            throw UsageError("--dem-normals", "needs the DEM: give a DEM or --reference DEM");
        Renderer renderer; // before the long work, so a machine without OpenGL says so at once
        std::optional<Heightfield> dem;
        Mesh mesh;
        if (is_mesh_path(args->input)) {
            mesh = read_mesh(args->input);
        } else {
            dem = args->raster.load(args->input);
            mesh = grid_tin(*dem);
        }
        if (!args->reference.empty())
            dem = args->raster.load(args->reference);

        RenderOptions options;
        options.wire = args->wire;
        options.depth = !args->depth.empty();
        options.scalar_max = args->scalar_max;
        // The colour-mapped renders carry a legend: the quantity and its units (world units are
        // metres; the SP stand-in is a distance on screen).
        const std::map<std::string, std::string> legends = {
            {"sp", "sp (px)"}, {"level", "quad-tree level"}, {"error", "vertical error (m)"}};
        if (const auto legend = legends.find(args->color); legend != legends.end())
            options.legend = legend->second;
        if (args->color == "height") {
            options.color = ColorMode::height;
        } else if (args->color == "sp") {
            options.color = ColorMode::vertex_scalar;
            options.vertex_scalar = node_screen_deviation(mesh, view);
            // A few nodes (spikes, the nearest ones) would squeeze every other colour into the
            // bottom of the map: top it at the 99th percentile instead of the maximum.
            if (options.scalar_max <= 0.0f && !options.vertex_scalar.empty()) {
                std::vector<float> sorted = options.vertex_scalar;
                auto top = sorted.begin() + std::ptrdiff_t(0.99 * double(sorted.size() - 1));
                std::nth_element(sorted.begin(), top, sorted.end());
                options.scalar_max = *top;
            }
        } else if (args->color == "level" || args->color == "error") {
            if (args->color == "level") {
                int deepest = 0;
                options.color = ColorMode::vertex_scalar;
                options.vertex_scalar = node_levels(mesh, *dem, deepest);
                if (options.scalar_max <= 0.0f)
                    options.scalar_max = float(deepest);
            } else {
                options.color = ColorMode::face_scalar;
                options.face_scalar = face_vertical_error(mesh, *dem);
            }
        }
        if (args->dem_normals)
            options.normal_source = &*dem;
        if (dem && options.color == ColorMode::height) {
            options.z_min = dem->min_z();
            options.z_max = dem->max_z();
        }
        const Image image = renderer.render(mesh, view, options);
        write_image(args->output, image);
        if (!args->depth.empty())
            write_depth(args->depth, image);
        std::printf("%s: %dx%d, %zu triangles, colour %s%s in %.0f ms (%s)\n", args->output.c_str(),
                    image.width, image.height, mesh.n_faces(), args->color.c_str(),
                    args->wire ? " + wire" : "", clock.ms(), renderer.gl_description().c_str());
    };
});

} // namespace tinlod::cli
