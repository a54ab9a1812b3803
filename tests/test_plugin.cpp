// The OpenMesh plugin: ModDistanceDecayT inside the stock DecimaterT (alone, beside
// ModNormalFlippingT, as a veto beside ModQuadricT) and NodeEraseDecimaterT, on a real DEM TIN.
#include "assets.hpp"

#include "tinlod/om/ModDistanceDecayT.hh"
#include "tinlod/om/NodeEraseDecimaterT.hh"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <gtest/gtest.h>

#include <algorithm>

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
    }
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
        OpenMesh::VPropHandleT<float> sp;
        EXPECT_TRUE(mesh.get_property_handle(sp, "tinlod:node_erase:sp"));
    }
    OpenMesh::VPropHandleT<float> sp;
    EXPECT_FALSE(mesh.get_property_handle(sp, "tinlod:node_erase:sp")); // owned for its lifetime
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

} // namespace
} // namespace tinlod
