// The OpenMesh plugin: ModDistanceDecayT inside the stock DecimaterT (alone, beside
// ModNormalFlippingT, as a veto beside ModQuadricT) and NodeEraseDecimaterT, on a real DEM TIN and
// on every scanned mesh in meshes/: the screen-space bound measured by the Hausdorff code, the
// same nodes as the library's (and the command line's) erase, recover() back to the input.
#include "assets.hpp"

#include "tinlod/hausdorff.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/om/ModDistanceDecayT.hh"
#include "tinlod/om/NodeEraseDecimaterT.hh"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <set>

namespace tinlod {
namespace {

using PlainMesh = OpenMesh::TriMesh_ArrayKernelT<>; // the stock default mesh type

struct Scene {
    Heightfield hf;
    View view;
    double split = 0.0; // median eye distance of the input nodes
};

Scene scene() {
    Scene s;
    s.hf = load_heightfield(test::asset("dem_squared.tif"));
    const double w = (s.hf.width - 1) * s.hf.dx, h = (s.hf.height - 1) * s.hf.dy;
    const double relief = s.hf.max_z() - s.hf.min_z();
    s.view.eye = {0.5 * w, -0.1 * h, s.hf.max_z() + 0.5 * relief};
    s.view.at = {0.5 * w, 0.7 * h, s.hf.min_z()};
    std::vector<double> d;
    for (int r = 0; r < s.hf.height; ++r)
        for (int c = 0; c < s.hf.width; ++c)
            d.push_back(
                glm::length(glm::dvec3(c * s.hf.dx, r * s.hf.dy, s.hf.at(c, r)) - s.view.eye));
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    s.split = d[d.size() / 2];
    return s;
}

template <class M> M copy_of(const Mesh &tin) {
    M out;
    for (auto v : tin.vertices()) {
        const auto &p = tin.point(v);
        out.add_vertex(typename M::Point(p[0], p[1], p[2]));
    }
    for (auto f : tin.faces()) {
        std::vector<typename M::VertexHandle> corners;
        for (auto v : f.vertices())
            corners.emplace_back(v.idx());
        out.add_face(corners);
    }
    return out;
}

// Live nodes nearer / farther than the split distance.
template <class M> std::pair<std::int64_t, std::int64_t> near_far(const M &mesh, const Scene &s) {
    std::int64_t near = 0, far = 0;
    for (auto v : mesh.vertices()) {
        if (mesh.has_vertex_status() && mesh.status(v).deleted())
            continue;
        const auto &p = mesh.point(v);
        (glm::length(glm::dvec3(p[0], p[1], p[2]) - s.view.eye) < s.split ? near : far) += 1;
    }
    return {near, far};
}

template <class M> std::int64_t folded(const M &mesh) {
    std::int64_t n = 0;
    for (auto f : mesh.faces()) {
        typename M::Point p[3];
        int i = 0;
        for (auto v : f.vertices())
            p[i++] = mesh.point(v);
        n += double(p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) -
                 double(p[2][0] - p[0][0]) * (p[1][1] - p[0][1]) <=
             0.0;
    }
    return n;
}

// The live faces of `mesh` as separate triangles (the Hausdorff measure needs no connectivity,
// and a soup takes any face OpenMesh holds).
template <class M> Mesh soup(const M &mesh) {
    Mesh out;
    for (auto f : mesh.faces()) {
        if (mesh.has_face_status() && mesh.status(f).deleted())
            continue;
        std::vector<Mesh::VertexHandle> corners;
        for (auto v : mesh.fv_range(f)) {
            const auto &p = mesh.point(v);
            corners.push_back(out.add_vertex(Mesh::Point(float(p[0]), float(p[1]), float(p[2]))));
        }
        out.add_face(corners);
    }
    return out;
}

// Float points measured in doubles: the bound up to rounding.
constexpr double k_px_slack = 1e-4;

template <class M> bool has_face_property(const M &mesh, const std::string &name) {
    for (auto it = mesh.fprops_begin(); it != mesh.fprops_end(); ++it)
        if (*it && (*it)->name() == name)
            return true;
    return false;
}

TEST(Plugin, StockDecimaterWithDistanceDecayKeepsNearNodes) {
    const Scene s = scene();
    PlainMesh mesh = copy_of<PlainMesh>(grid_tin(s.hf));
    mesh.request_vertex_status();
    mesh.request_edge_status();
    mesh.request_face_status();
    const auto before = near_far(mesh, s);
    {
        OpenMesh::Decimater::DecimaterT<PlainMesh> decimater(mesh);
        om::ModDistanceDecayT<PlainMesh>::Handle decay;
        ASSERT_TRUE(decimater.add(decay));
        decimater.module(decay).set_view(s.view);
        decimater.module(decay).set_tolerance(1.0);
        ASSERT_TRUE(decimater.initialize());
        EXPECT_GT(decimater.decimate(), 0u);
        EXPECT_TRUE(has_face_property(mesh, "tinlod:distance_decay:attached"));
    }
    EXPECT_FALSE(has_face_property(mesh, "tinlod:distance_decay:attached"))
        << "a module owns its property for exactly its lifetime";
    HausdorffOptions measure;
    measure.samples = 0; // the input's nodes: the bound is over them
    measure.model = Significance::screen(s.view);
    EXPECT_LE(hausdorff(grid_tin(s.hf), soup(mesh), measure).max_screen_px_a_to_b,
              1.0 + k_px_slack);
    mesh.garbage_collection();
    const auto after = near_far(mesh, s);
    EXPECT_LT(after.first + after.second, before.first + before.second);
    EXPECT_GT(double(after.first) / before.first, double(after.second) / before.second);
}

TEST(Plugin, ComposesWithNormalFlippingAndAsVetoBesideQuadric) {
    const Scene s = scene();
    for (bool binary : {false, true}) {
        PlainMesh mesh = copy_of<PlainMesh>(grid_tin(s.hf));
        mesh.request_vertex_status();
        mesh.request_edge_status();
        mesh.request_face_status();
        mesh.request_face_normals();
        mesh.update_face_normals();
        const auto before = near_far(mesh, s);
        {
            OpenMesh::Decimater::DecimaterT<PlainMesh> decimater(mesh);
            om::ModDistanceDecayT<PlainMesh>::Handle decay;
            OpenMesh::Decimater::ModNormalFlippingT<PlainMesh>::Handle flipping;
            OpenMesh::Decimater::ModQuadricT<PlainMesh>::Handle quadric;
            decimater.add(decay);
            decimater.add(flipping);
            if (binary) {
                decimater.add(quadric);
                decimater.module(quadric).unset_max_err();
            }
            decimater.module(decay).set_view(s.view);
            decimater.module(decay).set_tolerance(1.0);
            decimater.module(decay).set_binary(binary);
            decimater.module(flipping).set_max_normal_deviation(60.0);
            ASSERT_TRUE(decimater.initialize()) << "binary " << binary;
            EXPECT_GT(decimater.decimate(), 0u);
        }
        mesh.garbage_collection();
        const auto after = near_far(mesh, s);
        EXPECT_LT(after.first + after.second, before.first + before.second);
        EXPECT_GT(double(after.first) / before.first, double(after.second) / before.second)
            << "binary " << binary;
    }
}

TEST(Plugin, NodeEraseDecimaterOnStockMesh) {
    const Scene s = scene();
    PlainMesh mesh = copy_of<PlainMesh>(grid_tin(s.hf));
    const auto before = near_far(mesh, s);
    const std::int64_t euler = std::int64_t(mesh.n_vertices()) - std::int64_t(mesh.n_edges()) +
                               std::int64_t(mesh.n_faces());
    mesh.request_vertex_status(); // kept after the decimater goes, for garbage_collection()
    mesh.request_edge_status();
    mesh.request_face_status();
    {
        om::NodeEraseDecimaterT<PlainMesh> decimater(mesh);
        decimater.set_view(s.view);
        decimater.set_tolerance(1.0);
        ASSERT_TRUE(decimater.initialize());
        const std::size_t removed = decimater.decimate();
        EXPECT_GT(removed, 0u);
        EXPECT_EQ(decimater.n_live_vertices(), mesh.n_vertices() - removed);
    }
    ErrorOptions measure;
    measure.model = Significance::screen(s.view);
    const TinError error = measure_error(s.hf, soup(mesh), measure);
    EXPECT_LE(error.max_screen_px, 1.0 + k_px_slack);
    EXPECT_EQ(error.uncovered, 0);
    mesh.garbage_collection();
    const auto after = near_far(mesh, s);
    EXPECT_GT(double(after.first) / before.first, double(after.second) / before.second);
    EXPECT_EQ(folded(mesh), 0);
    EXPECT_EQ(std::int64_t(mesh.n_vertices()) - std::int64_t(mesh.n_edges()) +
                  std::int64_t(mesh.n_faces()),
              euler);
}

TEST(Plugin, NodeEraseDecimateToReachesTheCount) {
    const Scene s = scene();
    Mesh mesh = grid_tin(s.hf);
    const std::size_t target = mesh.n_vertices() / 5;
    om::NodeEraseDecimaterT<Mesh> decimater(mesh);
    decimater.set_view(s.view);
    decimater.set_tolerance(INFINITY);
    decimater.decimate_to(target);
    EXPECT_EQ(decimater.n_live_vertices(), target);
    mesh.garbage_collection(); // TinTraits carries status attributes of its own
    EXPECT_EQ(mesh.n_vertices(), target);
    EXPECT_EQ(test::count_folded_faces(mesh), 0);
}

// ---- The bound, the library's nodes and recover() on every scanned mesh -------------------------

// A scanned mesh of meshes/ and the camera it is seen from: on the +z side of its box, looking at
// its centre; the armadillo run 350 units away, the larger bunny close enough that part of
// it lies outside the frustum (where the peripheral factor relaxes the bound), the others whole in
// view.
struct Scan {
    std::string file;
    View view;
};

std::vector<Scan> scans() {
    std::vector<Scan> out;
    for (const char *file : {"bun_zipper_res4.ply", "bun_zipper_res2.ply", "armadillo.off",
                             "lion-head.off", "bull.off", "elephant.off"}) {
        PlainMesh mesh;
        EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, test::asset(file))) << file;
        glm::dvec3 lo(INFINITY), hi(-INFINITY);
        for (auto v : mesh.vertices()) {
            const auto &p = mesh.point(v);
            lo = glm::min(lo, glm::dvec3(p[0], p[1], p[2]));
            hi = glm::max(hi, glm::dvec3(p[0], p[1], p[2]));
        }
        const glm::dvec3 centre = 0.5 * (lo + hi);
        const std::string name = file;
        const double distance = name == "armadillo.off"         ? 350.0
                                : name == "bun_zipper_res2.ply" ? 0.6 * glm::length(hi - lo)
                                                                : 1.5 * glm::length(hi - lo);
        Scan s{file, {}};
        s.view.at = centre;
        s.view.eye = centre + distance * glm::normalize(glm::dvec3(0.2, 0.3, 1.0));
        std::int64_t outside = 0;
        for (auto v : mesh.vertices()) {
            const auto &p = mesh.point(v);
            outside += !s.view.in_frustum(glm::dvec3(p[0], p[1], p[2]));
        }
        EXPECT_EQ(outside > 0, name == "bun_zipper_res2.ply") << file;
        out.push_back(s);
    }
    return out;
}

PlainMesh read_plain(const std::string &file) {
    PlainMesh mesh;
    EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, test::asset(file))) << file;
    return mesh;
}

// The bound as the Hausdorff code measures it: the largest screen-space distance (pixels) from a
// vertex of the input to the output's surface, over the vertices inside the view frustum.
template <class M> double measured_px(const std::string &file, const M &output, const View &view) {
    HausdorffOptions options;
    options.samples = 0; // the input's vertices alone: the bound is over them
    options.model = Significance::screen(view);
    return hausdorff(read_mesh(test::asset(file)), soup(output), options).max_screen_px_a_to_b;
}

template <class M> std::size_t live_vertices(const M &mesh) {
    std::size_t n = 0;
    for (auto v : mesh.vertices())
        n += !mesh.status(v).deleted();
    return n;
}

// Each face as its corners' indices, rotated to start at the smallest (orientation kept).
template <class M> std::set<std::array<int, 3>> face_set(const M &mesh) {
    std::set<std::array<int, 3>> out;
    for (auto f : mesh.faces()) {
        if (mesh.has_face_status() && mesh.status(f).deleted())
            continue;
        std::array<int, 3> c{};
        int i = 0;
        for (auto v : mesh.fv_range(f))
            c[std::size_t(i++)] = v.idx();
        std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
        out.insert(c);
    }
    return out;
}

TEST(PluginScans, NodeEraseKeepsTheBoundGivesTheLibrarysNodesAndRecovers) {
    for (const Scan &scan : scans()) {
        SCOPED_TRACE(scan.file);
        const auto start = std::chrono::steady_clock::now();
        PlainMesh mesh = read_plain(scan.file);
        const std::set<std::array<int, 3>> input_faces = face_set(mesh);
        const std::size_t input_vertices = mesh.n_vertices();
        mesh.request_vertex_status(); // kept after the decimater goes, for garbage_collection()
        mesh.request_edge_status();
        mesh.request_face_status();

        // The library's path, as `tinlod simplify MESH` runs it.
        Mesh library = read_mesh(test::asset(scan.file));
        EraseOptions options;
        options.tolerance = 1.0;
        erase_nodes(library, Significance::screen(scan.view), options);
        const auto origin = find_origin_property(library);
        ASSERT_TRUE(origin.is_valid());
        std::set<std::int64_t> library_nodes;
        for (auto v : library.vertices())
            library_nodes.insert(library.property(origin, v));

        om::NodeEraseDecimaterT<PlainMesh> decimater(mesh);
        decimater.set_view(scan.view);
        decimater.set_tolerance(1.0);
        ASSERT_TRUE(decimater.initialize());
        const std::size_t erased = decimater.decimate();
        EXPECT_GT(erased, 0u);
        EXPECT_EQ(decimater.failed_faces(), 0u);
        EXPECT_EQ(live_vertices(mesh), input_vertices - erased);
        std::set<std::int64_t> plugin_nodes;
        for (auto v : mesh.vertices())
            if (!mesh.status(v).deleted())
                plugin_nodes.insert(v.idx());
        EXPECT_EQ(plugin_nodes, library_nodes);
        EXPECT_LE(measured_px(scan.file, mesh, scan.view), 1.0 + k_px_slack);

        EXPECT_EQ(decimater.recover(), erased);
        EXPECT_EQ(decimater.failed_faces(), 0u);
        EXPECT_EQ(live_vertices(mesh), input_vertices);
        EXPECT_EQ(face_set(mesh), input_faces);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_LT(seconds, 20.0);
    }
}

TEST(PluginScans, NodeEraseGivesTheCommandLinesNodes) {
    const Scan scan = scans()[1];
    const std::string out = test::temp_dir() + "/out.ply";
    char args[512];
    std::snprintf(args, sizeof args,
                  "simplify %s --eye %.17g,%.17g,%.17g --at %.17g,%.17g,%.17g -o %s",
                  test::asset(scan.file).c_str(), scan.view.eye.x, scan.view.eye.y, scan.view.eye.z,
                  scan.view.at.x, scan.view.at.y, scan.view.at.z, out.c_str());
    const test::RunResult run = test::run_cli(args);
    ASSERT_EQ(run.status, 0) << run.err;
    PlainMesh cli;
    ASSERT_TRUE(OpenMesh::IO::read_mesh(cli, out));

    PlainMesh mesh = read_plain(scan.file);
    om::NodeEraseDecimaterT<PlainMesh> decimater(mesh);
    decimater.set_view(scan.view);
    EXPECT_GT(decimater.decimate(), 0u);
    auto points = [](const PlainMesh &m) {
        std::multiset<std::array<float, 3>> out;
        for (auto v : m.vertices())
            if (!m.has_vertex_status() || !m.status(v).deleted())
                out.insert({m.point(v)[0], m.point(v)[1], m.point(v)[2]});
        return out;
    };
    EXPECT_EQ(points(mesh), points(cli));
}

// ModDistanceDecayT to its tolerance, alone (ordering by SP) and as a veto beside ModQuadricT:
// every input vertex stays within the tolerance, as the Hausdorff code measures it.
TEST(PluginScans, DistanceDecayKeepsTheBound) {
    for (const Scan &scan : scans()) {
        for (bool binary : {false, true}) {
            SCOPED_TRACE(scan.file + (binary ? " binary" : " ordering"));
            const auto start = std::chrono::steady_clock::now();
            PlainMesh mesh = read_plain(scan.file);
            mesh.request_vertex_status();
            mesh.request_edge_status();
            mesh.request_face_status();
            std::size_t collapses = 0;
            {
                OpenMesh::Decimater::DecimaterT<PlainMesh> decimater(mesh);
                om::ModDistanceDecayT<PlainMesh>::Handle decay;
                OpenMesh::Decimater::ModQuadricT<PlainMesh>::Handle quadric;
                decimater.add(decay);
                if (binary) {
                    decimater.add(quadric);
                    decimater.module(quadric).unset_max_err();
                }
                decimater.module(decay).set_view(scan.view);
                decimater.module(decay).set_tolerance(1.0);
                decimater.module(decay).set_binary(binary);
                ASSERT_TRUE(decimater.initialize());
                collapses = decimater.decimate();
            }
            EXPECT_GT(collapses, 0u);
            EXPECT_LE(measured_px(scan.file, mesh, scan.view), 1.0 + k_px_slack);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            EXPECT_LT(seconds, 20.0);
        }
    }
}

// decimate(n) stops after n erases; recover(v) brings one erased node back with the erases it
// depends on, and the mesh stays the library's (its recovered node live, no face refused).
TEST(PluginScans, NodeEraseByCountAndOneRecover) {
    const Scan scan = scans()[1];
    PlainMesh mesh = read_plain(scan.file);
    const std::size_t input_vertices = mesh.n_vertices();
    om::NodeEraseDecimaterT<PlainMesh> decimater(mesh);
    decimater.set_view(scan.view);
    EXPECT_EQ(decimater.decimate(100), 100u);
    EXPECT_EQ(live_vertices(mesh), input_vertices - 100);
    PlainMesh::VertexHandle erased;
    for (auto v : mesh.all_vertices())
        if (mesh.status(v).deleted())
            erased = v;
    ASSERT_TRUE(erased.is_valid());
    const std::size_t back = decimater.recover(erased);
    EXPECT_GE(back, 1u);
    EXPECT_FALSE(mesh.status(erased).deleted());
    EXPECT_FALSE(mesh.is_isolated(erased));
    EXPECT_EQ(decimater.failed_faces(), 0u);
    EXPECT_EQ(live_vertices(mesh), input_vertices - 100 + back);
    EXPECT_LE(measured_px(scan.file, mesh, scan.view), 1.0 + k_px_slack);
}

// A mesh whose add_face, once `refusing`, refuses the first triangle it is given every time it is
// given it, as OpenMesh refuses one it cannot join to a vertex's fans.
struct RefusingMesh : PlainMesh {
    using PlainMesh::add_face;
    bool refusing = false;
    std::array<int, 3> refused{-1, -1, -1};
    int refusals = 0;
    FaceHandle add_face(VertexHandle a, VertexHandle b, VertexHandle c) {
        std::array<int, 3> corners{a.idx(), b.idx(), c.idx()};
        std::sort(corners.begin(), corners.end());
        if (refusing && refused[0] < 0)
            refused = corners;
        if (refusing && corners == refused) {
            ++refusals;
            return FaceHandle();
        }
        return PlainMesh::add_face(a, b, c);
    }
};

template <class M> std::int64_t boundary_edges(const M &mesh) {
    std::int64_t n = 0;
    for (auto e : mesh.edges())
        n += mesh.is_boundary(e);
    return n;
}

// A triangle the write-back cannot add leaves no hole: the erases under it are undone, their nodes
// stay, and the output is a superset of the library's nodes with the bound kept.
TEST(PluginScans, NodeEraseUndoesTheErasesUnderARefusedTriangle) {
    const Scan scan = scans()[1];
    RefusingMesh mesh;
    ASSERT_TRUE(OpenMesh::IO::read_mesh(mesh, test::asset(scan.file)));
    const std::int64_t outline = boundary_edges(mesh);
    Mesh library = read_mesh(test::asset(scan.file));
    const EraseStats erased = erase_nodes(library, Significance::screen(scan.view), EraseOptions{});

    om::NodeEraseDecimaterT<RefusingMesh> decimater(mesh);
    decimater.set_view(scan.view);
    mesh.refusing = true;
    const std::size_t removed = decimater.decimate();
    EXPECT_GT(mesh.refusals, 0);
    EXPECT_EQ(decimater.failed_faces(), 0u);
    EXPECT_GT(removed, 0u);
    EXPECT_LT(std::int64_t(removed), erased.erased);
    for (auto v : mesh.vertices()) {
        if (mesh.status(v).deleted()) {
            EXPECT_TRUE(mesh.is_isolated(v));
        }
    }
    EXPECT_EQ(boundary_edges(mesh), outline); // no hole: a surface mesh's outline never moves
    EXPECT_LE(measured_px(scan.file, mesh, scan.view), 1.0 + k_px_slack);
}

} // namespace
} // namespace tinlod
