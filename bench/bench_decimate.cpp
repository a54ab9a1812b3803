// Side by side, in one run, from one fixed view and to the same output node count: tinlod's node
// erase (lib/decimate) against meshoptimizer's meshopt_simplify (on the whole N42E001 grid TIN) and
// OpenMesh's stock DecimaterT + ModQuadricT + ModNormalFlippingT (on a 513x513 crop: the stock
// decimater needs tens of seconds on the whole tile). Prints time, input triangles per second,
// xy fold-overs and the exhaustively measured screen-space error (measure_error), with ratios to
// tinlod; then the view-independent mode's node counts for 1, 5 and 20 m.
//
// Usage: bench_decimate [DEM] (default: meshes/N42E001.hgt).
#include "tinlod/decimate.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/util.hpp"

#include "common.hpp"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <meshoptimizer.h>

#include <cstdio>
#include <string>

namespace {

using namespace tinlod;

struct Row {
    std::string name;
    double ms = 0.0;
    std::int64_t input_triangles = 0, nodes = 0, triangles = 0, folded = 0;
    double max_screen_px = 0.0;
};

View bench_view(const Heightfield &hf) {
    const double w = (hf.width - 1) * hf.dx, h = (hf.height - 1) * hf.dy;
    View view;
    view.eye = {0.3 * w, -0.05 * h, hf.max_z() + 500.0};
    view.at = {0.6 * w, 0.6 * h, hf.min_z()};
    return view;
}

Row measure(const std::string &name, const Heightfield &hf, const View &view, const Mesh &out,
            double ms, std::int64_t input_triangles) {
    Row row{name,
            ms,
            input_triangles,
            std::int64_t(out.n_vertices()),
            std::int64_t(out.n_faces()),
            bench::folded_faces(out),
            0.0};
    ErrorOptions eo;
    eo.model = Significance::screen(view);
    row.max_screen_px = measure_error(hf, out, eo).max_screen_px;
    return row;
}

Row run_tinlod(const Heightfield &hf, const View &view, double tol, std::int64_t max_nodes) {
    Mesh tin = grid_tin(hf);
    const std::int64_t tris = std::int64_t(tin.n_faces());
    EraseOptions options;
    options.tolerance = tol;
    options.max_nodes = max_nodes;
    Stopwatch clock;
    erase_nodes(tin, Significance::screen(view), options);
    const double ms = clock.ms();
    return measure(max_nodes ? "tinlod erase (node budget)" : "tinlod erase (tau = 1 px)", hf, view,
                   tin, ms, tris);
}

Row run_meshopt(const Heightfield &hf, const View &view, std::int64_t target_nodes) {
    const Mesh tin = grid_tin(hf);
    std::vector<float> xyz;
    xyz.reserve(tin.n_vertices() * 3);
    for (auto v : tin.vertices())
        for (int k = 0; k < 3; ++k)
            xyz.push_back(tin.point(v)[k]);
    std::vector<unsigned> indices;
    for (auto f : tin.faces())
        for (auto v : f.vertices())
            indices.push_back(unsigned(v.idx())); // = grid sample id
    std::vector<unsigned> out(indices.size());
    Stopwatch clock;
    const std::size_t n = meshopt_simplify(out.data(), indices.data(), indices.size(), xyz.data(),
                                           tin.n_vertices(), 12, std::size_t(target_nodes) * 6,
                                           1.0f, meshopt_SimplifyLockBorder, nullptr);
    const double ms = clock.ms();
    out.resize(n);
    return measure("meshopt_simplify (lock border)", hf, view, tin_from_indices(hf, out), ms,
                   std::int64_t(indices.size() / 3));
}

Row run_openmesh(const Heightfield &hf, const View &view, std::int64_t target_nodes) {
    Mesh tin = grid_tin(hf);
    const std::int64_t tris = std::int64_t(tin.n_faces());
    tin.request_face_normals();
    tin.update_face_normals();
    Stopwatch clock;
    {
        OpenMesh::Decimater::DecimaterT<Mesh> decimater(tin);
        OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
        OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle flipping;
        decimater.add(quadric);
        decimater.add(flipping);
        decimater.module(quadric).unset_max_err();
        decimater.initialize();
        decimater.decimate_to(std::size_t(target_nodes));
    }
    tin.garbage_collection();
    const double ms = clock.ms();
    return measure("OpenMesh DecimaterT+Quadric+NormalFlip", hf, view, tin, ms, tris);
}

void print(const std::string &title, const std::vector<Row> &rows) {
    std::printf("\n%s\n", title.c_str());
    std::printf("%-40s %10s %10s %9s %9s %7s %10s %8s %8s\n", "method", "ms", "Mtris/s", "nodes",
                "tris", "folded", "max px", "time x", "error x");
    const Row &ref = rows.front();
    for (const Row &r : rows)
        std::printf("%-40s %10.1f %10.2f %9lld %9lld %7lld %10.3f %8.2f %8.2f\n", r.name.c_str(),
                    r.ms, r.input_triangles / r.ms / 1000.0, static_cast<long long>(r.nodes),
                    static_cast<long long>(r.triangles), static_cast<long long>(r.folded),
                    r.max_screen_px, r.ms / ref.ms,
                    r.max_screen_px / std::max(ref.max_screen_px, 1e-12));
}

} // namespace

int main(int argc, char **argv) {
    std::string path = argc > 1 ? argv[1] : std::string(__FILE__);
    if (argc <= 1) // meshes/ beside bench/ in the source tree
        path = path.substr(0, path.rfind("bench/")) + "meshes/N42E001.hgt";
    const Heightfield hf = load_heightfield(path);
    const View view = bench_view(hf);
    std::printf("DEM %s: %dx%d, view eye (%.0f, %.0f, %.0f) at (%.0f, %.0f, %.0f), k = %.1f\n",
                path.c_str(), hf.width, hf.height, view.eye.x, view.eye.y, view.eye.z, view.at.x,
                view.at.y, view.at.z, view.k());

    std::vector<Row> whole;
    whole.push_back(run_tinlod(hf, view, 1.0, 0));
    const std::int64_t target = whole.front().nodes;
    whole.push_back(run_meshopt(hf, view, target));
    print("Whole tile, same node count as tinlod at tau = 1 px (ratios to tinlod):", whole);

    const Heightfield small = bench::crop(hf, 513, 513);
    const View small_view = bench_view(small);
    std::vector<Row> cropped;
    cropped.push_back(run_tinlod(small, small_view, 1.0, 0));
    const std::int64_t small_target = cropped.front().nodes;
    cropped.push_back(run_meshopt(small, small_view, small_target));
    cropped.push_back(run_openmesh(small, small_view, small_target));
    print("513x513 crop, same node count as tinlod at tau = 1 px (ratios to tinlod):", cropped);

    {
        // The erase history the refiner builds on: its size, and recovering every node.
        Mesh tin = grid_tin(hf);
        NodeEraser eraser(tin, Significance::screen(view), EraseOptions{});
        const EraseStats stats = eraser.erase();
        const double bytes = double(eraser.history_bytes()) / double(stats.input_nodes);
        Stopwatch clock;
        const std::int64_t recovered = eraser.recover_all();
        const double ms = clock.ms();
        std::printf("\nErase history: %.1f bytes per input node beside the mesh; recover_all: %lld "
                    "nodes in %.0f ms (%.2f M nodes/s)\n",
                    bytes, static_cast<long long>(recovered), ms, recovered / ms / 1000.0);
    }

    std::printf("\nView-independent (--max-error: erase_dem from the DEM), whole tile:\n"
                "%10s %10s %10s %10s %12s %10s\n",
                "bound m", "first", "nodes", "ms", "Mtris/s", "measured m");
    const double grid_tris = 2.0 * (hf.width - 1) * (hf.height - 1);
    for (double bound : {1.0, 5.0, 20.0}) {
        EraseOptions options;
        options.tolerance = bound;
        DemEraseStats st;
        Stopwatch clock;
        const Mesh tin = erase_dem(hf, Significance::vertical(), options, {}, &st);
        const double ms = clock.ms();
        std::printf("%10.1f %10s %10zu %10.0f %12.2f %10.3f\n", bound,
                    first_stage_name(st.first_stage), tin.n_vertices(), ms, grid_tris / ms / 1000.0,
                    measure_error(hf, tin).max_vertical);
    }
    return 0;
}
