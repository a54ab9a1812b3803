// What the third round of `simplify --max-error` speed-ups relies on
// (docs/decisions/027-simplify-speed-3.md): the binary STL written directly is OpenMesh's, byte
// for byte, and reads back; measure_error over each row's run between a triangle's edges gives
// what a test of every sample of its box gives; add_triangles still refuses a directed edge used
// twice, found now in its twin search.
#include "assets.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/greedy.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <vector>

using namespace tinlod;
using tinlod::test::asset;

namespace {

// A greedy TIN of a crop of N42E001 to a vertical bound, as `simplify --max-error` starts from.
Mesh greedy_mesh(const Heightfield &hf, double bound) {
    GreedyOptions go;
    go.max_error = bound;
    return to_sparse_lattice_mesh(greedy_tin(hf, go).tin, hf);
}

Heightfield n42_crop(int x0, int y0, int side) {
    return test::crop(load_heightfield(asset("N42E001.hgt")), x0, y0, side, side);
}

// Triangles by their corners' points, each from its least point (a file renumbers the vertices).
std::set<std::array<std::array<float, 3>, 3>> triangles(const Mesh &m) {
    std::set<std::array<std::array<float, 3>, 3>> set;
    for (auto f : m.faces()) {
        std::array<std::array<float, 3>, 3> t;
        int i = 0;
        for (auto v : f.vertices())
            t[std::size_t(i++)] = {m.point(v)[0], m.point(v)[1], m.point(v)[2]};
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        set.insert(t);
    }
    return set;
}

// The reference: every sample of each triangle's box tested, as measure_error did before it
// bounded each row's run (vertical model; the first triangle to cover a sample takes it).
TinError box_scan(const Heightfield &hf, const Mesh &tin, const View *view) {
    TinError out;
    std::vector<std::uint8_t> covered(std::size_t(hf.size()), 0);
    double sum_sq = 0.0;
    const auto snap = [](double g) {
        const double n = std::round(g);
        return std::abs(g - n) < 1e-3 ? n : g;
    };
    for (auto f : tin.faces()) {
        std::array<std::array<double, 3>, 3> t;
        int i = 0;
        for (auto v : f.vertices()) {
            const auto &p = tin.point(v);
            t[std::size_t(i++)] = {snap(p[0] / hf.dx), snap(p[1] / hf.dy), p[2]};
        }
        const double area =
            (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]);
        if (std::abs(area) < 1e-12)
            continue;
        const double eps = 1e-7 * std::abs(area);
        const int c0 = std::max(0, int(std::ceil(std::min({t[0][0], t[1][0], t[2][0]}) - 1e-6)));
        const int c1 =
            std::min(hf.width - 1, int(std::floor(std::max({t[0][0], t[1][0], t[2][0]}) + 1e-6)));
        const int r0 = std::max(0, int(std::ceil(std::min({t[0][1], t[1][1], t[2][1]}) - 1e-6)));
        const int r1 =
            std::min(hf.height - 1, int(std::floor(std::max({t[0][1], t[1][1], t[2][1]}) + 1e-6)));
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c) {
                const double w0 = (t[1][0] - c) * (t[2][1] - r) - (t[2][0] - c) * (t[1][1] - r);
                const double w1 = (t[2][0] - c) * (t[0][1] - r) - (t[0][0] - c) * (t[2][1] - r);
                const double w2 = area - w0 - w1;
                const bool inside = area > 0 ? (w0 >= -eps && w1 >= -eps && w2 >= -eps)
                                             : (w0 <= eps && w1 <= eps && w2 <= eps);
                const std::size_t id = std::size_t(r) * std::size_t(hf.width) + std::size_t(c);
                if (!inside || covered[id])
                    continue;
                covered[id] = 1;
                const double z = (w0 * t[0][2] + w1 * t[1][2] + w2 * t[2][2]) / area;
                const double dz = std::abs(double(hf.z[id]) - z);
                ++out.samples;
                sum_sq += dz * dz;
                if (dz > out.max_vertical) {
                    out.max_vertical = dz;
                    if (!view)
                        out.worst_sample = std::int64_t(id);
                }
                if (view && dz > 0.0) {
                    const glm::dvec3 p(c * hf.dx, r * hf.dy, double(hf.z[id]));
                    if (!view->in_frustum(p))
                        continue;
                    const double px = dz * view->k() / glm::length(p - view->eye);
                    if (px > out.max_screen_px) {
                        out.max_screen_px = px;
                        out.worst_sample = std::int64_t(id);
                    }
                }
            }
    }
    out.uncovered = std::count(covered.begin(), covered.end(), std::uint8_t(0));
    if (out.samples > 0)
        out.rms_vertical = std::sqrt(sum_sq / double(out.samples));
    return out;
}

void expect_same(const TinError &a, const TinError &b) {
    EXPECT_EQ(a.max_vertical, b.max_vertical);
    EXPECT_EQ(a.rms_vertical, b.rms_vertical);
    EXPECT_EQ(a.max_screen_px, b.max_screen_px);
    EXPECT_EQ(a.samples, b.samples);
    EXPECT_EQ(a.uncovered, b.uncovered);
    EXPECT_EQ(a.worst_sample, b.worst_sample);
}

} // namespace

// A greedy TIN (lattice corners), the bunny (a surface, any normal) and an erased grid TIN holding
// deleted elements (written as its live part): each file is the one OpenMesh writes, and reads
// back to the same triangles.
TEST(SimplifySpeed3, BinaryStlIsOpenMeshsAndReadsBack) {
    const Heightfield hf = n42_crop(300, 500, 129);
    Mesh greedy = greedy_mesh(hf, 4.0);
    Mesh bunny = read_mesh(asset("bun_zipper_res2.ply"));
    Mesh erased = grid_tin(hf);
    EraseOptions eo;
    eo.tolerance = 6.0;
    NodeEraser(erased, Significance::vertical(), eo).erase();
    ASSERT_LT(std::distance(erased.faces_sbegin(), erased.faces_end()),
              std::ptrdiff_t(erased.n_faces()));
    const std::string dir = test::temp_dir();
    for (Mesh *mesh : {&greedy, &bunny, &erased}) {
        write_mesh(*mesh, dir + "/ours.stl");
        Mesh live = *mesh;
        live.garbage_collection();
        OpenMesh::IO::Options binary;
        binary += OpenMesh::IO::Options::Binary;
        omlog().disable(); // its writer announces itself
        ASSERT_TRUE(OpenMesh::IO::write_mesh(live, dir + "/openmesh.stl", binary));
        omlog().enable();
        const std::string ours = test::file_bytes(dir + "/ours.stl");
        EXPECT_EQ(ours.size(), 84 + 50 * live.n_faces());
        EXPECT_TRUE(ours == test::file_bytes(dir + "/openmesh.stl"));
        const Mesh back = read_mesh(dir + "/ours.stl");
        EXPECT_EQ(back.n_faces(), live.n_faces());
        EXPECT_EQ(triangles(back), triangles(live));
    }
}

// Lattice TINs (greedy, and erased from the grid at a vertical bound), the same read back from a
// file (float corners a hair off the lattice, snapped), one with corners off the lattice, and a
// view's screen error: the same figures, to the last bit, as the box scan.
TEST(SimplifySpeed3, MeasureErrorIsTheBoxScans) {
    for (const auto &[x0, y0] : {std::pair{0, 0}, std::pair{700, 260}}) {
        SCOPED_TRACE(std::to_string(x0) + "," + std::to_string(y0));
        const Heightfield hf = n42_crop(x0, y0, 201);
        Mesh erased = grid_tin(hf);
        EraseOptions eo;
        eo.tolerance = 3.0;
        NodeEraser(erased, Significance::vertical(), eo).erase();
        erased.garbage_collection();
        const std::string dir = test::temp_dir();
        write_mesh(erased, dir + "/erased.ply");
        Mesh shifted = greedy_mesh(hf, 2.0);
        std::mt19937 rng(27);
        std::uniform_real_distribution<float> jitter(-0.3f, 0.3f);
        for (auto v : shifted.vertices()) {
            auto p = shifted.point(v);
            const bool inner = p[0] > 0.0f && p[1] > 0.0f && p[0] < float((hf.width - 1) * hf.dx) &&
                               p[1] < float((hf.height - 1) * hf.dy);
            if (inner) // the outline stays, so the TIN still covers the crop
                shifted.set_point(v, p + Mesh::Point(jitter(rng) * float(hf.dx),
                                                     jitter(rng) * float(hf.dy), 0.0f));
        }
        View view;
        view.eye = {-200.0, -300.0, 3000.0};
        view.at = {0.5 * hf.width * hf.dx, 0.5 * hf.height * hf.dy, 1000.0};
        ErrorOptions seen;
        seen.model = Significance::screen(view);
        const std::vector<Mesh> meshes = {greedy_mesh(hf, 1.0), erased,
                                          read_mesh(dir + "/erased.ply"), shifted};
        for (std::size_t i = 0; i < meshes.size(); ++i) {
            SCOPED_TRACE(i);
            const TinError measured = measure_error(hf, meshes[i]);
            EXPECT_GT(measured.samples, 0);
            expect_same(measured, box_scan(hf, meshes[i], nullptr));
            const TinError from_view = measure_error(hf, meshes[i], seen);
            EXPECT_GT(from_view.max_screen_px, 0.0);
            expect_same(from_view, box_scan(hf, meshes[i], &view));
        }
    }
}

// A directed edge used twice, with no side the other way (two open sides into one vertex), with
// two the other way, or met again after its twin was paired: refused, the mesh left as it was.
TEST(SimplifySpeed3, AddTrianglesRefusesADirectedEdgeUsedTwice) {
    Mesh points;
    for (int i = 0; i < 5; ++i)
        points.add_vertex(Mesh::Point(float(i % 3), float(i * i % 5), 0.0f));
    for (const std::vector<std::uint32_t> &corners : {std::vector<std::uint32_t>{0, 1, 2, 0, 1, 3},
                                                      {0, 1, 2, 1, 0, 3, 1, 0, 4},
                                                      {1, 0, 3, 0, 1, 2, 1, 0, 4}}) {
        Mesh m = points;
        EXPECT_THROW(add_triangles(m, corners), std::invalid_argument);
        EXPECT_EQ(m.n_faces(), 0u);
        EXPECT_EQ(m.n_edges(), 0u);
    }
}
