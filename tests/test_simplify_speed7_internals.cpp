// What the seventh round of `simplify --max-error` speed-ups relies on
// (docs/decisions/038-simplify-speed-7-floor.md), each against a computation written here or the
// path it replaces: face_worst over a small face's box gives what a scan of the closed triangle's
// rows gives; the greedy insertion's TIN paired by its own twins is the mesh add_triangles builds
// from the same triangles; live_copy, pairing by the source's half-edges, is the copy add_triangles
// builds from its faces; nodes_left, pairing by the arrays' neighbours, is the mesh add_vertex and
// add_triangles build from the live nodes and triangles.
#include "assets.hpp"

#include "erase/hole_geometry.hpp"
#include "erase/lattice_scan.hpp"
#include "erase/state.hpp"
#include "erase/tin_arrays.hpp"
#include "lattice_triangle.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/greedy.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace tinlod;
using namespace tinlod::erase;
using tinlod::test::asset;

namespace {

// Every element's connectivity and every vertex's point and origin, in index order: two meshes
// with equal fingerprints are the same arrays.
std::vector<double> fingerprint(const Mesh &m) {
    std::vector<double> out = {double(m.n_vertices()), double(m.n_edges()), double(m.n_faces())};
    const auto origin = find_origin_property(m);
    for (auto v : m.all_vertices()) {
        const auto &p = m.point(v);
        out.insert(out.end(),
                   {double(p[0]), double(p[1]), double(p[2]), double(m.halfedge_handle(v).idx()),
                    origin.is_valid() ? double(m.property(origin, v)) : -1.0});
    }
    for (auto h : m.all_halfedges())
        out.insert(out.end(),
                   {double(m.to_vertex_handle(h).idx()), double(m.next_halfedge_handle(h).idx()),
                    double(m.prev_halfedge_handle(h).idx()), double(m.face_handle(h).idx())});
    for (auto f : m.all_faces())
        out.push_back(double(m.halfedge_handle(f).idx()));
    return out;
}

// The largest deviation of a face's samples other than its corners (and the first sample with it,
// in row order), from LatticeTriangle's row spans and the plane's deviation with the face's margin,
// as the eraser defines a face's worst sample.
std::pair<float, std::int32_t> worst_by_rows(const EraserState &s, std::uint32_t a, std::uint32_t b,
                                             std::uint32_t c, const TrianglePlane &plane,
                                             double margin) {
    const LatticeTriangle t(s.input.grid_w, a, b, c);
    double most = 0.0;
    std::int32_t worst = -1;
    for (std::int64_t r = t.first_row; r <= t.last_row; ++r) {
        const auto [lo, hi] = t.span(r);
        for (std::int64_t x = lo; x <= hi; ++x) {
            const auto u = std::uint32_t(r * s.input.grid_w + x);
            const Mesh::Point &p = s.input.mesh->point(VH(int(u)));
            const double d = plane.deviation(p[0], p[1], p[2], margin);
            if (u != a && u != b && u != c && d > most) {
                most = d;
                worst = std::int32_t(u);
            }
        }
    }
    return {float_up(most), worst};
}

// The greedy insertion's TINs of crops of real DEMs, at fine and coarse bounds.
std::vector<std::pair<Heightfield, GreedyTin>> greedy_tins() {
    std::vector<std::pair<Heightfield, GreedyTin>> out;
    const Heightfield srtm =
        test::crop(load_heightfield(asset("dem_srtm30.tif")), 20, 30, 200, 160);
    const Heightfield crater =
        test::crop(load_heightfield(asset("crater_u16.png")), 40, 60, 180, 200);
    for (const Heightfield *hf : {&srtm, &crater})
        for (const double m : {1.0, 5.0, 20.0}) {
            GreedyOptions go;
            go.max_error = m;
            go.seed_step = 16;
            out.emplace_back(*hf, greedy_tin(*hf, go));
        }
    return out;
}

} // namespace

// Random faces on a lattice of random heights, their boxes from 2 to 24 samples a side (over and
// under k_small_box), both orientations given: face_worst's deviation and sample are the rows'.
TEST(SimplifySpeed7, FaceWorstIsTheWorstOfTheRows) {
    std::mt19937 rng(38);
    constexpr std::uint32_t w = 48, h = 40;
    Mesh mesh;
    std::uniform_real_distribution<double> height(-50.0, 400.0);
    for (std::uint32_t r = 0; r < h; ++r)
        for (std::uint32_t c = 0; c < w; ++c)
            mesh.add_vertex(Mesh::Point(float(1000.0 + 30.0 * c), float(-2000.0 + 30.0 * r),
                                        float(height(rng))));
    EraserState s;
    s.input.mesh = &mesh;
    s.input.grid_w = w;
    s.input.nodes = w * h;
    int small = 0, large = 0, with_samples = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const std::int64_t side = std::uniform_int_distribution<std::int64_t>(2, 24)(rng);
        std::uniform_int_distribution<std::int64_t> cx(0, w - side), cy(0, h - side),
            in(0, side - 1);
        const std::int64_t x0 = cx(rng), y0 = cy(rng);
        std::int64_t x[3], y[3];
        for (int k = 0; k < 3; ++k) {
            x[k] = x0 + in(rng);
            y[k] = y0 + in(rng);
        }
        const std::int64_t o = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        if (o == 0)
            continue;
        if (o < 0) { // the eraser's faces are counter-clockwise
            std::swap(x[1], x[2]);
            std::swap(y[1], y[2]);
        }
        std::uint32_t ids[3];
        glm::dvec3 p[3];
        for (int k = 0; k < 3; ++k) {
            ids[k] = std::uint32_t(y[k] * w + x[k]);
            const Mesh::Point &q = mesh.point(VH(int(ids[k])));
            p[k] = glm::dvec3(q[0], q[1], q[2]);
        }
        const TriangleFrame frame = triangle_frame(glm::dvec2(p[0]), glm::dvec2(p[1]),
                                                   glm::dvec2(p[2]), true, p[0].z, p[1].z, p[2].z);
        const auto got = face_worst(s, ids[0], ids[1], ids[2], frame, p[0], p[1], p[2]);
        const auto expected = worst_by_rows(s, ids[0], ids[1], ids[2], frame.plane,
                                            frame.plane.margin_over(p[0], p[1], p[2]));
        ASSERT_EQ(got, expected) << "corners " << ids[0] << " " << ids[1] << " " << ids[2];
        (box_samples(x, y) <= k_small_box ? small : large) += 1;
        with_samples += expected.second >= 0;
    }
    EXPECT_GT(small, 1000);
    EXPECT_GT(large, 1000);
    EXPECT_GT(with_samples, 2000);
}

// The insertion's TIN paired by its twins is, array for array, the mesh of the same triangles
// whose twins add_triangles searches for (the Retrieval's to_sparse_lattice_mesh).
TEST(SimplifySpeed7, GreedyMeshByTwinsIsTheSearchedMesh) {
    for (const auto &[hf, greedy] : greedy_tins()) {
        ASSERT_EQ(greedy.twin.size(), greedy.tin.triangles.size());
        const Mesh paired = to_sparse_lattice_mesh(greedy, hf);
        EXPECT_GT(paired.n_faces(), 100u);
        EXPECT_EQ(fingerprint(paired), fingerprint(to_sparse_lattice_mesh(greedy.tin, hf)));
    }
}

// The erase of a greedy TIN leaves deleted vertices, edges and faces: live_copy of it is, array for
// array, the mesh add_triangles builds from its live vertices and its faces' corners.
TEST(SimplifySpeed7, LiveCopyIsAddTrianglesOfTheLiveFaces) {
    for (const auto &[hf, greedy] : greedy_tins()) {
        Mesh mesh = to_sparse_lattice_mesh(greedy, hf);
        EraseOptions eo;
        eo.tolerance = 10.0; // erases some, keeps some
        eo.lattice = &hf;
        const EraseStats erased = NodeEraser(mesh, Significance::vertical(), eo).erase();
        EXPECT_GT(erased.erased, 0);
        // The reference: the live vertices in order, then add_triangles over the faces' corners.
        Mesh expected;
        const auto from = find_origin_property(mesh);
        const auto to = get_origin_property(expected);
        std::vector<std::uint32_t> map(mesh.n_vertices()), corners;
        for (auto v : mesh.vertices()) {
            const Mesh::VertexHandle w = expected.add_vertex(mesh.point(v));
            expected.property(to, w) = mesh.property(from, v);
            map[std::size_t(v.idx())] = std::uint32_t(w.idx());
        }
        for (auto f : mesh.faces())
            for (auto v : f.vertices())
                corners.push_back(map[std::size_t(v.idx())]);
        add_triangles(expected, corners);
        const Mesh copy = live_copy(mesh);
        EXPECT_LT(copy.n_faces(), mesh.n_faces());
        EXPECT_EQ(fingerprint(copy), fingerprint(expected));
    }
}

namespace {

// Erases each interior node of three triangles in the arrays (its hole, one triangle, takes its
// first triangle's slot; the other two slots are freed), as the passes leave them. Returns how
// many.
int erase_nodes_of_three(TinArrays &tin) {
    int erased = 0;
    std::vector<std::int32_t> ring, triangles;
    std::vector<int> edge;
    for (std::size_t v = 0; v < tin.fan.size(); ++v) {
        if (tin.outline[v] || !tin.star(std::int32_t(v), 3, ring, triangles, edge) ||
            ring.size() != 3)
            continue;
        // Triangle i is (v, ring[i], ring[i + 1]); its outer edge ring[i] -> ring[i + 1].
        std::int32_t outer[3];
        for (int i = 0; i < 3; ++i)
            outer[i] = tin.across[3 * std::size_t(triangles[i]) + std::size_t(edge[i])];
        const std::int32_t t = triangles[0];
        for (int i = 0; i < 3; ++i) {
            tin.corner[3 * std::size_t(t) + std::size_t(i)] = ring[i];
            tin.across[3 * std::size_t(t) + std::size_t(i)] = outer[i];
            tin.fan[std::size_t(ring[i])] = t;
            if (outer[i] >= 0) // the neighbour's side back along ring[i + 1] -> ring[i]
                tin.across[3 * std::size_t(outer[i]) +
                           std::size_t(tin.index_of(outer[i], ring[(i + 1) % 3]))] = t;
        }
        for (int i = 1; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
                tin.corner[3 * std::size_t(triangles[i]) + std::size_t(k)] = -1;
        tin.fan[v] = -1;
        ++erased;
    }
    return erased;
}

} // namespace

// nodes_left pairs each side with the side of the triangle across it: array for array, the mesh
// add_vertex and add_triangles build from the live nodes in order and the live triangles' corners.
TEST(SimplifySpeed7, NodesLeftIsAddTrianglesOfTheLiveTriangles) {
    int erased_in_all = 0;
    for (const auto &[hf, greedy] : greedy_tins()) {
        const Mesh source = to_sparse_lattice_mesh(greedy, hf);
        TinArrays tin = tin_arrays(source, hf);
        for (std::size_t v = 0; v < tin.z.size(); ++v)
            tin.z[v] += 0.25 * double(v % 3); // heights off the mesh's, as the free heights leave
        const int erased = erase_nodes_of_three(tin);
        erased_in_all += erased;
        Mesh expected;
        const auto origin = get_origin_property(expected);
        std::vector<std::uint32_t> map(tin.fan.size()), corners;
        for (std::size_t v = 0; v < tin.fan.size(); ++v)
            if (tin.fan[v] >= 0) {
                Mesh::Point p = source.point(VH(int(v)));
                p[2] = float(tin.z[v]);
                const VH w = expected.add_vertex(p);
                expected.property(origin, w) = tin.sample[v];
                map[v] = std::uint32_t(w.idx());
            }
        for (std::size_t i = 0; i < tin.corner.size(); i += 3)
            if (tin.corner[i] >= 0)
                for (std::size_t k = 0; k < 3; ++k)
                    corners.push_back(map[std::size_t(tin.corner[i + k])]);
        add_triangles(expected, corners);
        const Mesh left = nodes_left(tin, source);
        EXPECT_EQ(left.n_faces(), source.n_faces() - 2 * std::size_t(erased));
        EXPECT_EQ(fingerprint(left), fingerprint(expected));
    }
    EXPECT_GT(erased_in_all, 10); // freed slots and erased nodes met
}
