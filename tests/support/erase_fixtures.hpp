// Test helpers over erased TINs, shared by the erase's tests (test_decimate) and the tests of its
// internals: triangle sets, the invariants of a TIN, cropped DEM assets and a view over them,
// the stats of a `simplify` run.
#pragma once

#include "assets.hpp"

#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace tinlod::test {

// The --stats of `tinlod simplify DEM ARGS` (DEM in meshes/), its output in a fresh temporary
// folder; the run is expected to succeed.
inline nlohmann::json simplify_stats(const std::string &dem, const std::string &args) {
    const std::string dir = temp_dir(), path = asset(dem);
    const RunResult r = run_cli("simplify '" + path + "' " + args + " -o '" + dir +
                                "/out.ply' --stats '" + dir + "/stats.json'");
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(std::ifstream(dir + "/stats.json"));
}

using Triangle = std::array<std::int64_t, 3>;

// Live triangles as origin-id triples rotated to start at the smallest id, sorted.
inline std::vector<Triangle> triangle_set(Mesh &mesh) {
    auto origin = get_origin_property(mesh);
    std::vector<Triangle> out;
    for (auto f : mesh.faces()) {
        Triangle t;
        int i = 0;
        for (auto v : f.vertices())
            t[i++] = mesh.property(origin, v);
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
}

struct Invariants {
    std::int64_t euler = 0;
    std::int64_t non_manifold = 0;
    std::int64_t boundary_edges = 0;
    double boundary_length = 0.0; // xy length of the outline
};

inline Invariants invariants(const Mesh &mesh) {
    Invariants inv;
    std::int64_t v = 0, e = 0, f = 0;
    for (auto vh : mesh.vertices()) {
        ++v;
        inv.non_manifold += !mesh.is_manifold(vh);
    }
    for (auto eh : mesh.edges()) {
        ++e;
        if (mesh.is_boundary(eh)) {
            ++inv.boundary_edges;
            const auto d = mesh.calc_edge_vector(eh);
            inv.boundary_length += std::hypot(double(d[0]), double(d[1]));
        }
    }
    for (auto fh : mesh.faces()) {
        ++f;
        (void)fh;
    }
    inv.euler = v - e + f;
    return inv;
}

struct DemAsset {
    const char *file;
    bool terrain_rgb;
    int crop; // 0: whole raster
};

inline Heightfield load_cropped(const DemAsset &a) {
    LoadOptions lo;
    lo.terrain_rgb = a.terrain_rgb;
    Heightfield hf = load_heightfield(asset(a.file), lo);
    if (a.crop == 0 || (a.crop >= hf.width && a.crop >= hf.height))
        return hf;
    return crop(hf, 0, 0, std::min(a.crop, hf.width), std::min(a.crop, hf.height));
}

// A view from above the south-west corner looking north-east across the terrain.
inline View corner_view(const Heightfield &hf) {
    const double w = (hf.width - 1) * hf.dx, h = (hf.height - 1) * hf.dy;
    View view;
    view.eye = {-0.05 * w, -0.05 * h, hf.max_z() + 0.15 * std::max(w, h)};
    view.at = {0.6 * w, 0.6 * h, hf.min_z()};
    return view;
}

// N42E001's 201² corner as a grid TIN, its triangles, and its corner view.
struct CornerCrop {
    Heightfield hf = load_cropped({"N42E001.hgt", false, 201});
    View view = corner_view(hf);
    Mesh input = grid_tin(hf);
    std::vector<Triangle> triangles = triangle_set(input);
};

// A pass after the erase took `before` to `after` on hf: every sample within `bound` (measured by
// measure_error, not the pass), none uncovered, no fold, the same outline, fewer triangles, and
// two triangles gone with each interior node.
inline void expect_fewer_within(const Heightfield &hf, const Mesh &before, const Mesh &after,
                                double bound) {
    const TinError error = measure_error(hf, after);
    EXPECT_LE(error.max_vertical, bound);
    EXPECT_EQ(error.uncovered, 0);
    EXPECT_EQ(count_folded_faces(after), 0);
    EXPECT_NEAR(xy_area(after), xy_area(before), 1e-6 * xy_area(before));
    EXPECT_LT(after.n_faces(), before.n_faces());
    EXPECT_EQ(before.n_faces() - after.n_faces(), 2 * (before.n_vertices() - after.n_vertices()));
}

} // namespace tinlod::test
