// Foundation: the full-resolution grid TIN and mesh files in and out.
#include "assets.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/tin.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

using namespace tinlod;
using tinlod::test::asset;

TEST(GridTin, CountsManifoldAndCounterClockwise) {
    for (const char *file : {"dem_squared.tif", "crater_u16.png", "dem_srtm30.tif"}) {
        SCOPED_TRACE(file);
        const Heightfield hf = load_heightfield(asset(file));
        const Mesh mesh = grid_tin(hf);
        EXPECT_EQ(mesh.n_vertices(), std::size_t(hf.width) * hf.height);
        EXPECT_EQ(mesh.n_faces(), 2 * std::size_t(hf.width - 1) * (hf.height - 1));
        EXPECT_EQ(tinlod::test::count_folded_faces(mesh), 0);
        std::int64_t boundary = 0;
        for (auto e : mesh.edges()) {
            boundary += mesh.is_boundary(e);
            EXPECT_TRUE(mesh.is_manifold(mesh.from_vertex_handle(mesh.halfedge_handle(e, 0))));
        }
        EXPECT_EQ(boundary, 2 * (hf.width - 1) + 2 * (hf.height - 1));
        EXPECT_NEAR(tinlod::test::xy_area(mesh), (hf.width - 1) * hf.dx * (hf.height - 1) * hf.dy,
                    1e-6 * hf.width * hf.dx * hf.height * hf.dy);
        // Provenance: node i is sample i, standing where the sample is.
        auto origin = find_origin_property(mesh);
        ASSERT_TRUE(origin.is_valid());
        for (auto v : mesh.vertices()) {
            const std::int64_t id = mesh.property(origin, v);
            EXPECT_EQ(mesh.point(v)[2], hf.z[std::size_t(id)]);
        }
        // The grid TIN is the reference: zero error against its own DEM, every sample covered.
        const TinError err = measure_error(hf, mesh);
        EXPECT_EQ(err.max_vertical, 0.0);
        EXPECT_EQ(err.uncovered, 0);
        EXPECT_EQ(err.samples, hf.size());
    }
}

static std::set<std::array<std::int64_t, 3>> triangle_set(const Mesh &mesh) {
    std::set<std::array<std::int64_t, 3>> set;
    for (auto f : mesh.faces()) {
        std::array<std::int64_t, 3> t;
        int i = 0;
        for (auto v : f.vertices())
            t[i++] = v.idx();
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        set.insert(t);
    }
    return set;
}

TEST(MeshIo, RoundTripThroughEachFormatKeepsVerticesAndFaces) {
    const Heightfield hf = load_heightfield(asset("dem_squared.tif"));
    const Mesh mesh = grid_tin(hf);
    const std::string dir = tinlod::test::temp_dir();
    for (const char *ext : {".ply", ".obj", ".off"}) {
        SCOPED_TRACE(ext);
        const std::string path = dir + "/grid" + ext;
        write_mesh(mesh, path);
        MeshReport report;
        const Mesh back = read_mesh(path, &report);
        EXPECT_EQ(back.n_vertices(), mesh.n_vertices());
        EXPECT_EQ(back.n_faces(), mesh.n_faces());
        EXPECT_EQ(triangle_set(back), triangle_set(mesh));
        for (auto v : mesh.vertices())
            EXPECT_EQ(back.point(v), mesh.point(v)) << "vertex " << v.idx();
        EXPECT_EQ(report.non_manifold_edges, 0);
    }
    // STL stores triangle soups: faces survive, vertices are welded back by position.
    write_mesh(mesh, dir + "/grid.stl");
    const Mesh stl = read_mesh(dir + "/grid.stl");
    EXPECT_EQ(stl.n_faces(), mesh.n_faces());
    EXPECT_EQ(stl.n_vertices(), mesh.n_vertices());
}

// A real DEM's grid TIN erased in place to 2 m: most vertices, edges and faces marked deleted, the
// live ones spread over the arrays (as in a refiner's TIN between frames).
static Mesh erased_in_place(std::int64_t *erased_nodes = nullptr) {
    const Heightfield hf = load_heightfield(asset("crater_u16.png"));
    Mesh erased = grid_tin(hf);
    EraseOptions eo;
    eo.tolerance = 2.0;
    const EraseStats e = NodeEraser(erased, Significance::vertical(), eo).erase();
    if (erased_nodes)
        *erased_nodes = e.erased;
    return erased;
}

static void expect_written_live_part(const Mesh &erased) {
    const auto live_vertices =
        std::size_t(std::distance(erased.vertices_sbegin(), erased.vertices_end()));
    const auto live_faces = std::size_t(std::distance(erased.faces_sbegin(), erased.faces_end()));
    ASSERT_LT(live_vertices, erased.n_vertices());
    ASSERT_LT(live_faces, erased.n_faces());
    // Triangles by their corners' points (files renumber the vertices), each from its least point.
    using Corner = std::array<float, 3>;
    const auto triangles = [](const Mesh &m) {
        std::set<std::array<Corner, 3>> set;
        for (auto f : m.faces()) {
            std::array<Corner, 3> t;
            int i = 0;
            for (auto v : f.vertices())
                t[i++] = {m.point(v)[0], m.point(v)[1], m.point(v)[2]};
            std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
            set.insert(t);
        }
        return set;
    };
    const std::string dir = tinlod::test::temp_dir();
    for (const char *ext : {".ply", ".obj", ".off"}) {
        SCOPED_TRACE(ext);
        write_mesh(erased, dir + "/erased" + ext);
        const Mesh back = read_mesh(dir + "/erased" + ext);
        EXPECT_EQ(back.n_vertices(), live_vertices);
        EXPECT_EQ(back.n_faces(), live_faces);
        EXPECT_EQ(triangles(back), triangles(erased));
    }
}

// A file gets the live part of a mesh holding deleted elements, and only it: a grid TIN's, and a
// scanned surface's, some of whose vertices join two boundary fans.
TEST(MeshIo, WritesTheLivePartOfAMeshWithDeletedElements) {
    View view;
    view.eye = {0.3, 0.12, 0.4};
    view.at = {-0.02, 0.1, 0.0};
    Mesh bunny = read_mesh(asset("bun_zipper_res2.ply"));
    NodeEraser(bunny, Significance::screen(view), EraseOptions{}).erase();
    {
        SCOPED_TRACE("crater_u16 grid TIN");
        expect_written_live_part(erased_in_place());
    }
    SCOPED_TRACE("bun_zipper_res2");
    expect_written_live_part(bunny);
}
TEST(MeshIo, NonManifoldBunnyLoadsAndIsReported) {
    // MANIFEST: bun_zipper_res4.ply has 453 vertices, 948 faces and 70 non-manifold edges.
    MeshReport report;
    const Mesh mesh = read_mesh(asset("bun_zipper_res4.ply"), &report);
    EXPECT_EQ(report.faces, 948);
    EXPECT_EQ(report.non_manifold_edges, 70);
    EXPECT_EQ(report.vertices, 453 + report.duplicated_vertices);
    EXPECT_GT(report.duplicated_vertices, 0);
    EXPECT_EQ(mesh.n_faces(), 948u); // no face dropped: split onto duplicated vertices instead
}

TEST(MeshIo, UnwritablePathsThrowAndLeaveNothing) {
    const Heightfield hf = load_heightfield(asset("dem_squared.tif"));
    const Mesh mesh = grid_tin(hf);
    const std::string dir = tinlod::test::temp_dir();
    EXPECT_THROW(write_mesh(mesh, dir + "/no/such/folder/out.ply"), Error);
    EXPECT_THROW(write_mesh(mesh, dir + "/out.xyz"), Error);
    EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(GridTin, SurfaceHeightMatchesTheTinAndRefusesEyesInside) {
    const Heightfield hf = load_heightfield(asset("dem_squared.tif"));
    // At every sample the surface is the sample; between them it interpolates the grid TIN, so it
    // agrees with measure_error's rasterisation: a TIN is its own surface.
    for (int r = 0; r < hf.height; r += 7)
        for (int c = 0; c < hf.width; c += 5)
            EXPECT_NEAR(*grid_surface_height(hf, c * hf.dx, r * hf.dy), hf.at(c, r), 1e-3);
    const double x = 40.25 * hf.dx, y = 70.6 * hf.dy;
    const float corners[4] = {hf.at(40, 70), hf.at(41, 70), hf.at(40, 71), hf.at(41, 71)};
    const double z = *grid_surface_height(hf, x, y);
    EXPECT_GE(z, *std::min_element(corners, corners + 4));
    EXPECT_LE(z, *std::max_element(corners, corners + 4));
    EXPECT_FALSE(grid_surface_height(hf, -1.0, y).has_value());
    EXPECT_THROW(check_eye_above(hf, {x, y, z - 1.0}, "--eye"), Error);
    EXPECT_NO_THROW(check_eye_above(hf, {x, y, z + 1.0}, "--eye"));
    EXPECT_NO_THROW(check_eye_above(hf, {-500.0, y, 0.0}, "--eye")); // outside, beside the terrain
}

namespace {

// Every face's corners from its half-edge (face order and rotation kept), each vertex's ring as
// the sorted list of its neighbours, and the boundary vertices: what add_face and add_triangles
// must agree on, whatever order they give the edges in.
struct Topology {
    std::vector<std::array<int, 3>> faces;
    std::vector<std::vector<int>> rings;
    std::vector<bool> boundary;
    bool operator==(const Topology &) const = default;
};

Topology topology(const Mesh &mesh) {
    Topology t;
    for (auto f : mesh.faces()) {
        auto h = mesh.halfedge_handle(f);
        std::array<int, 3> c{};
        for (int &k : c) {
            k = mesh.from_vertex_handle(h).idx();
            h = mesh.next_halfedge_handle(h);
        }
        EXPECT_EQ(h, mesh.halfedge_handle(f)); // a triangle's half-edges close after three
        t.faces.push_back(c);
    }
    for (auto v : mesh.vertices()) {
        std::vector<int> ring;
        for (auto w : mesh.vv_range(v))
            ring.push_back(w.idx());
        const std::size_t walked = ring.size();
        std::sort(ring.begin(), ring.end());
        // The circulator walks the whole fan from the vertex's outgoing half-edge: each neighbour
        // once, none missed because the walk started inside a boundary fan.
        EXPECT_EQ(std::unique(ring.begin(), ring.end()), ring.end());
        EXPECT_EQ(walked, ring.size());
        t.rings.push_back(ring);
        t.boundary.push_back(mesh.is_boundary(v));
    }
    return t;
}

Mesh with_vertices_of(const Mesh &mesh) {
    Mesh out;
    for (auto v : mesh.vertices())
        out.add_vertex(mesh.point(v));
    return out;
}

} // namespace

TEST(AddTriangles, BuildsTheMeshAddFaceBuilds) {
    // A real DEM's grid (boundary all round), then the same with a hole: a second boundary loop,
    // and vertices on it whose first face in the list is not next to the hole.
    const Heightfield hf = load_heightfield(asset("crater_u16.png"));
    const Mesh grid = grid_tin(hf);
    for (const bool hole : {false, true}) {
        SCOPED_TRACE(hole ? "with a hole" : "whole");
        Mesh by_face = with_vertices_of(grid), by_array = with_vertices_of(grid);
        std::vector<std::uint32_t> corners;
        for (auto f : grid.faces()) {
            const glm::dvec3 c =
                (face_corners(grid, f)[0] + face_corners(grid, f)[1] + face_corners(grid, f)[2]) /
                3.0;
            if (hole && std::abs(c.x / hf.dx - hf.width / 2.0) < hf.width / 5.0 &&
                std::abs(c.y / hf.dy - hf.height / 2.0) < hf.height / 7.0)
                continue;
            for (auto v : grid.fv_range(f))
                corners.push_back(std::uint32_t(v.idx()));
        }
        for (std::size_t i = 0; i < corners.size(); i += 3)
            by_face.add_face(Mesh::VertexHandle(int(corners[i])),
                             Mesh::VertexHandle(int(corners[i + 1])),
                             Mesh::VertexHandle(int(corners[i + 2])));
        add_triangles(by_array, corners);
        ASSERT_EQ(by_array.n_faces(), by_face.n_faces());
        EXPECT_EQ(by_array.n_edges(), by_face.n_edges());
        EXPECT_TRUE(topology(by_array) == topology(by_face));
        // Every boundary vertex leaves by a boundary half-edge, as OpenMesh's edits expect (those
        // in the hole have none).
        for (auto v : by_array.vertices()) {
            if (!by_array.is_isolated(v) && by_array.is_boundary(v)) {
                EXPECT_TRUE(by_array.is_boundary(by_array.halfedge_handle(v)));
            }
        }
        // Boundary loops are linked: next and prev of a boundary half-edge follow the loop.
        for (auto h : by_array.halfedges()) {
            const auto next = by_array.next_halfedge_handle(h);
            EXPECT_EQ(by_array.prev_halfedge_handle(next), h);
            EXPECT_EQ(by_array.from_vertex_handle(next), by_array.to_vertex_handle(h));
            EXPECT_EQ(by_array.is_boundary(next), by_array.is_boundary(h));
        }
        // OpenMesh's own edits then agree: the same face deleted in both, garbage collected.
        for (Mesh *m : {&by_face, &by_array}) {
            m->request_face_status();
            m->request_edge_status();
            m->request_vertex_status();
            m->delete_face(Mesh::FaceHandle(0));
            m->garbage_collection();
        }
        EXPECT_TRUE(topology(by_array) == topology(by_face));
    }
}

TEST(LiveCopy, GivesTheMeshGarbageCollectionGives) {
    // OpenMesh's own compaction is the reference.
    std::int64_t erased_nodes = 0;
    const Mesh erased = erased_in_place(&erased_nodes);
    ASSERT_GT(erased_nodes, std::int64_t(erased.n_vertices() / 2));
    const Mesh copy = live_copy(erased);
    Mesh collected = erased;
    collected.garbage_collection();
    ASSERT_EQ(copy.n_vertices(), collected.n_vertices());
    ASSERT_EQ(copy.n_faces(), collected.n_faces());
    EXPECT_EQ(copy.n_edges(), collected.n_edges());
    // garbage_collection fills holes from the end of the arrays; live_copy keeps the input's
    // order. So the two are compared through each node's origin (its grid sample).
    struct Described {
        std::vector<std::pair<std::int64_t, Mesh::Point>> nodes; // origin, point
        std::set<std::array<std::int64_t, 3>> faces; // origins, from the smallest, in order
        std::set<std::int64_t> boundary;
    };
    const auto describe = [](const Mesh &m) {
        Described d;
        const auto origin = find_origin_property(m);
        EXPECT_TRUE(origin.is_valid());
        for (auto v : m.vertices()) {
            d.nodes.emplace_back(m.property(origin, v), m.point(v));
            if (m.is_boundary(v))
                d.boundary.insert(m.property(origin, v));
        }
        for (auto f : m.faces()) {
            std::array<std::int64_t, 3> c{};
            auto h = m.halfedge_handle(f);
            for (auto &k : c) {
                k = m.property(origin, m.from_vertex_handle(h));
                h = m.next_halfedge_handle(h);
            }
            std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
            d.faces.insert(c);
        }
        return d;
    };
    const Described a = describe(copy);
    Described b = describe(collected);
    // live_copy keeps the input's order: origins ascend, as the grid TIN's vertex ids.
    EXPECT_TRUE(std::is_sorted(a.nodes.begin(), a.nodes.end(),
                               [](const auto &x, const auto &y) { return x.first < y.first; }));
    std::sort(b.nodes.begin(), b.nodes.end(),
              [](const auto &x, const auto &y) { return x.first < y.first; });
    EXPECT_TRUE(a.nodes == b.nodes);
    EXPECT_EQ(a.faces.size(), copy.n_faces());
    EXPECT_TRUE(a.faces == b.faces);
    EXPECT_TRUE(a.boundary == b.boundary);
}

TEST(AddTriangles, RefusesWhatIsNotAnOrientedManifold) {
    Mesh square;
    for (const auto &p : {Mesh::Point(0, 0, 0), Mesh::Point(1, 0, 0), Mesh::Point(1, 1, 0),
                          Mesh::Point(0, 1, 0), Mesh::Point(2, 2, 0), Mesh::Point(2, 1, 0)})
        square.add_vertex(p);
    const auto fails = [&](std::vector<std::uint32_t> corners) {
        Mesh m = square;
        EXPECT_THROW(add_triangles(m, corners), std::invalid_argument);
    };
    fails({0, 1, 2, 0, 2, 3, 3, 2, 0}); // edge 0 -> 2... used twice in the same direction
    fails({0, 1, 2, 0, 3, 2});          // a face flipped against its neighbour
    fails({0, 1, 2, 2, 5, 4});          // two fans meet at vertex 2 only (a bow-tie)
    // Two closed fans at one vertex: two tetrahedra sharing vertex 0, no boundary at all.
    Mesh apex;
    for (int i = 0; i < 7; ++i)
        apex.add_vertex(Mesh::Point(float(i), float(i * i % 5), float(i % 3)));
    const std::vector<std::uint32_t> tetrahedra = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2,
                                                   0, 4, 5, 0, 5, 6, 0, 6, 4, 4, 6, 5};
    EXPECT_THROW(add_triangles(apex, tetrahedra), std::invalid_argument);
    EXPECT_EQ(apex.n_faces(), 0u);
    add_triangles(apex, std::span(tetrahedra).first(12)); // one tetrahedron alone is closed
    EXPECT_EQ(apex.n_faces(), 4u);
    EXPECT_EQ(apex.n_edges(), 6u);
    fails({0, 1, 6}); // a corner out of range
    fails({0, 1, 1}); // a repeated corner
    fails({0, 1});    // a partial triangle
    Mesh m = square;
    add_triangles(m, std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
    EXPECT_EQ(m.n_faces(), 2u);
    EXPECT_EQ(m.n_edges(), 5u);
    EXPECT_THROW(add_triangles(m, std::vector<std::uint32_t>{0, 1, 2}), std::invalid_argument);
}

TEST(AddTriangles, IndexListsThatAreNotManifoldsGoInFaceByFace) {
    // A peer's output may repeat a directed edge: tin_from_indices keeps what OpenMesh's add_face
    // accepts, here the first two of three triangles over a 3x2 grid (the third reuses 0 -> 1).
    Heightfield hf;
    hf.width = 3;
    hf.height = 2;
    hf.z = {0, 1, 2, 3, 4, 5};
    const Mesh mesh = tin_from_indices(hf, {0, 1, 4, 0, 4, 3, 0, 1, 3});
    EXPECT_EQ(mesh.n_faces(), 2u);
    EXPECT_EQ(mesh.n_vertices(), 4u);
    const Mesh clean = tin_from_indices(hf, {0, 1, 4, 0, 4, 3});
    EXPECT_EQ(topology(mesh), topology(clean));
}
