// The quad-tree and its view-dependent retrieval: layout of any size, node bounds, the screen-space
// error bound measured over every sample, crack-freeness, and the monotonic behaviour in tau and
// distance, on the real DEMs of meshes/.
#include "assets.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/quadtree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

using namespace tinlod;
using namespace tinlod::test;

namespace {

struct Asset {
    std::string name;
    LoadOptions options;
};

std::vector<Asset> dem_assets() {
    LoadOptions rgb;
    rgb.terrain_rgb = true;
    return {{"N42E001.hgt", {}},
            {"dem_squared.tif", {}},
            {"dem_srtm30.tif", {}},
            {"crater_u16.png", {}},
            {"fuji.png", rgb}};
}

const Heightfield &dem(const Asset &a) {
    static std::map<std::string, Heightfield> cache;
    auto it = cache.find(a.name);
    if (it == cache.end())
        it = cache.emplace(a.name, load_heightfield(asset(a.name), a.options)).first;
    return it->second;
}

View make_view(glm::dvec3 eye, glm::dvec3 at) {
    View v;
    v.eye = eye;
    v.at = at;
    return v;
}

struct NamedView {
    std::string name;
    View view;
};

// Near the ground looking across, high above looking down, and outside the terrain.
std::vector<NamedView> views_of(const Heightfield &hf) {
    const double ex = (hf.width - 1) * hf.dx, ey = (hf.height - 1) * hf.dy;
    const double zlo = hf.min_z(), zhi = hf.max_z(), relief = std::max(zhi - zlo, 1.0);
    const double span = std::max(ex, ey);
    const int c = hf.width / 10, r = hf.height / 10;
    const double ground = hf.at(c, r);
    return {{"low", make_view({c * hf.dx, r * hf.dy, ground + std::max(2.0, 0.01 * relief)},
                              {0.6 * ex, 0.7 * ey, hf.at(hf.width * 6 / 10, hf.height * 7 / 10)})},
            {"high", make_view({0.5 * ex, 0.45 * ey, zhi + span}, {0.5 * ex, 0.5 * ey, zlo})},
            {"outside", make_view({-0.3 * ex, -0.2 * ey, zhi + 0.1 * span},
                                  {0.5 * ex, 0.5 * ey, 0.5 * (zlo + zhi)})}};
}

// Manifold, CCW, covering exactly the terrain rectangle, with its boundary on the outline.
void expect_crack_free(const Heightfield &hf, const Retrieval &r, const std::string &what) {
    const Mesh mesh = tin_from_indices(hf, r.triangles);
    EXPECT_EQ(mesh.n_faces() * 3, r.triangles.size()) << what << ": non-manifold triangles";
    EXPECT_EQ(mesh.n_vertices(), r.nodes.size()) << what;
    EXPECT_EQ(count_folded_faces(mesh), 0) << what;
    const double area = double(hf.width - 1) * hf.dx * double(hf.height - 1) * hf.dy;
    EXPECT_NEAR(xy_area(mesh), area, 1e-6 * area) << what;
    // A disc: V - E + F = 1, and every boundary edge runs along the outline.
    const auto v = std::int64_t(mesh.n_vertices()), e = std::int64_t(mesh.n_edges()),
               f = std::int64_t(mesh.n_faces());
    EXPECT_EQ(v - e + f, 1) << what;
    double perimeter = 0;
    for (auto h : mesh.halfedges()) {
        if (!mesh.is_boundary(h))
            continue;
        const auto a = mesh.point(mesh.from_vertex_handle(h)),
                   b = mesh.point(mesh.to_vertex_handle(h));
        perimeter += std::hypot(double(b[0] - a[0]), double(b[1] - a[1]));
        const bool west = a[0] == 0 && b[0] == 0, south = a[1] == 0 && b[1] == 0;
        const bool east = a[0] == float((hf.width - 1) * hf.dx) && b[0] == a[0];
        const bool north = a[1] == float((hf.height - 1) * hf.dy) && b[1] == a[1];
        EXPECT_TRUE(west || south || east || north) << what << ": inner boundary edge";
    }
    const double outline = 2 * ((hf.width - 1) * hf.dx + (hf.height - 1) * hf.dy);
    EXPECT_NEAR(perimeter, outline, 1e-5 * outline) << what;
}

} // namespace

TEST(AxisSplit, PartitionsEveryLevelDownToCells) {
    for (int n : {2, 3, 4, 5, 9, 17, 30, 129, 300, 459, 1201}) {
        const AxisSplit a(n, AxisSplit::levels_for(n));
        for (int d = 0; d < a.levels(); ++d) {
            ASSERT_EQ(a.lo(d, 0), 0u);
            ASSERT_EQ(a.hi(d, a.count(d) - 1), std::uint32_t(n - 1));
            std::uint32_t shortest = ~0u, longest = 0;
            for (std::uint32_t k = 0; k < a.count(d); ++k) {
                ASSERT_LT(a.lo(d, k), a.hi(d, k));
                if (k > 0) {
                    ASSERT_EQ(a.lo(d, k), a.hi(d, k - 1));
                }
                shortest = std::min(shortest, a.length(d, k));
                longest = std::max(longest, a.length(d, k));
                if (d > 0) {
                    const std::uint32_t p = a.parent(d, k);
                    ASSERT_GE(a.lo(d, k), a.lo(d - 1, p));
                    ASSERT_LE(a.hi(d, k), a.hi(d - 1, p));
                }
            }
            EXPECT_LE(longest - shortest, 1u) << "n=" << n << " level " << d;
            if (d == a.levels() - 1) {
                EXPECT_EQ(longest, 1u) << "n=" << n;
            }
        }
    }
}

TEST(QuadTree, PlaneHasZeroBoundsAndGivesTheRoot) {
    Heightfield hf;
    hf.width = 37;
    hf.height = 22;
    for (int r = 0; r < hf.height; ++r)
        for (int c = 0; c < hf.width; ++c)
            hf.z.push_back(float(2 * c - 3 * r + 100));
    const QuadTree tree(hf);
    EXPECT_EQ(tree.bound(0, 0, 0).error, 0.0f);
    EXPECT_EQ(tree.bound(0, 0, 0).zmin, hf.min_z());
    EXPECT_EQ(tree.bound(0, 0, 0).zmax, hf.max_z());
    const Retrieval r = retrieve(tree, make_view({18, 10, 101}, {30, 20, 100}), {0.01, false});
    EXPECT_EQ(r.nodes.size(), 5u);
    EXPECT_EQ(r.triangles.size(), 12u);
    expect_crack_free(hf, r, "plane");
}

TEST(QuadTree, SpikeBoundIsItsHeight) {
    Heightfield hf;
    hf.width = 9;
    hf.height = 9;
    hf.z.assign(81, 0.0f);
    hf.at(2, 3) = 1.5f;
    const QuadTree tree(hf);
    EXPECT_EQ(tree.bound(0, 0, 0).error, 1.5f);
    // The 4x4-cell child holding the spike, and the other three children are flat.
    EXPECT_EQ(tree.bound(1, 0, 0).error, 1.5f);
    EXPECT_EQ(tree.bound(1, 1, 0).error, 0.0f);
    EXPECT_EQ(tree.bound(1, 0, 1).error, 0.0f);
    EXPECT_EQ(tree.bound(1, 1, 1).error, 0.0f);
}

TEST(QuadTree, BoundsAreMonotoneAndBoxesNested) {
    for (const Asset &a : dem_assets()) {
        const QuadTree tree(dem(a));
        const QuadLayout &lay = tree.layout();
        for (int d = 0; d + 2 < lay.levels(); ++d)
            for (std::uint32_t j = 0; j < lay.y.count(d); ++j)
                for (std::uint32_t i = 0; i < lay.x.count(d); ++i) {
                    const NodeBound &p = tree.bound(d, i, j);
                    if (lay.is_cell(d, i, j))
                        continue;
                    const std::uint32_t cx = lay.x.first_child(d, i), cy = lay.y.first_child(d, j);
                    for (std::uint32_t b = 0; b < (lay.y.length(d, j) >= 2 ? 2u : 1u); ++b)
                        for (std::uint32_t c = 0; c < (lay.x.length(d, i) >= 2 ? 2u : 1u); ++c) {
                            const NodeBound &ch = tree.bound(d + 1, cx + c, cy + b);
                            ASSERT_GE(p.error, ch.error) << a.name;
                            ASSERT_LE(p.zmin, ch.zmin) << a.name;
                            ASSERT_GE(p.zmax, ch.zmax) << a.name;
                        }
                }
    }
}

// A node's z box is the least and largest of its samples, exactly: the build folds the children's
// boxes into their parent's instead of reading the samples again.
TEST(QuadTree, BoxesAreTheExtremesOfTheNodesSamples) {
    for (const Asset &a : dem_assets()) {
        const Heightfield &hf = dem(a);
        const QuadTree tree(hf);
        const QuadLayout &lay = tree.layout();
        for (int d = 0; d + 1 < lay.levels(); ++d)
            for (std::uint32_t j = 0; j < lay.y.count(d); ++j)
                for (std::uint32_t i = 0; i < lay.x.count(d); ++i) {
                    float lo = INFINITY, hi = -INFINITY;
                    for (std::uint32_t r = lay.y.lo(d, j); r <= lay.y.hi(d, j); ++r)
                        for (std::uint32_t c = lay.x.lo(d, i); c <= lay.x.hi(d, i); ++c) {
                            lo = std::min(lo, hf.at(int(c), int(r)));
                            hi = std::max(hi, hf.at(int(c), int(r)));
                        }
                    ASSERT_EQ(tree.bound(d, i, j).zmin, lo) << a.name << " level " << d;
                    ASSERT_EQ(tree.bound(d, i, j).zmax, hi) << a.name << " level " << d;
                }
    }
}

// Built from a raster it takes over (`tinlod build`), the tree is the one built from a copy.
TEST(QuadTree, TakingTheRasterOverBuildsTheSameTree) {
    for (const Asset &a : dem_assets()) {
        const QuadTree copied(dem(a));
        Heightfield raster = dem(a);
        const QuadTree taken(std::move(raster));
        ASSERT_EQ(taken.elevations(), dem(a).z) << a.name;
        ASSERT_EQ(taken.layout().levels(), copied.layout().levels()) << a.name;
        const QuadLayout &lay = copied.layout();
        for (int d = 0; d + 1 < lay.levels(); ++d)
            for (std::uint32_t j = 0; j < lay.y.count(d); ++j)
                for (std::uint32_t i = 0; i < lay.x.count(d); ++i) {
                    const NodeBound &x = copied.bound(d, i, j), &y = taken.bound(d, i, j);
                    ASSERT_EQ(x.error, y.error) << a.name;
                    ASSERT_EQ(x.zmin, y.zmin) << a.name;
                    ASSERT_EQ(x.zmax, y.zmax) << a.name;
                }
    }
}

TEST(Retrieve, ScreenErrorWithinToleranceOnEveryAssetAndView) {
    for (const Asset &a : dem_assets()) {
        const Heightfield &hf = dem(a);
        const QuadTree tree(hf);
        QuadTreeLod lod(tree);
        for (const NamedView &nv : views_of(hf))
            for (double tol : {0.5, 1.0, 4.0}) {
                const Retrieval &r = lod.retrieve(nv.view, {tol, false});
                const std::string what = a.name + " " + nv.name + " tol " + std::to_string(tol);
                ErrorOptions eo;
                eo.model = Significance::screen(nv.view);
                eo.frustum_only = false;
                const TinError err = measure_error(hf, r.triangles, eo);
                EXPECT_EQ(err.uncovered, 0) << what;
                EXPECT_LE(err.max_screen_px, tol * (1 + 1e-9)) << what;
                EXPECT_LE(r.bound_px, tol) << what;
                EXPECT_LT(r.nodes.size(), std::size_t(hf.size())) << what;
            }
    }
}

TEST(Retrieve, CrackFreeOnEveryAssetAndView) {
    for (const Asset &a : dem_assets()) {
        const Heightfield &hf = dem(a);
        const QuadTree tree(hf);
        for (const NamedView &nv : views_of(hf))
            expect_crack_free(hf, retrieve(tree, nv.view, {1.0, false}), a.name + " " + nv.name);
    }
}

TEST(Retrieve, AnySizeIsCrackFreeAndWithinTolerance) {
    const Heightfield &src = dem({"dem_squared.tif", {}});
    for (auto [w, h] : {std::pair{2, 2},
                        {2, 9},
                        {9, 2},
                        {3, 17},
                        {37, 5},
                        {65, 65},
                        {100, 33},
                        {128, 129},
                        {129, 77}}) {
        const Heightfield hf = crop(src, 0, 0, w, h);
        const QuadTree tree(hf);
        for (const NamedView &nv : views_of(hf))
            for (double tol : {0.0, 0.5, 4.0}) {
                const Retrieval r = retrieve(tree, nv.view, {tol, false});
                const std::string what = std::to_string(w) + "x" + std::to_string(h) + " " +
                                         nv.name + " tol " + std::to_string(tol);
                expect_crack_free(hf, r, what);
                ErrorOptions eo;
                eo.model = Significance::screen(nv.view);
                eo.frustum_only = false;
                EXPECT_LE(measure_error(hf, r.triangles, eo).max_screen_px, tol * (1 + 1e-9))
                    << what;
            }
    }
}

TEST(Retrieve, ZeroToleranceGivesTheFullGridAndHugeGivesTheRoot) {
    for (const Asset &a : dem_assets()) {
        const Heightfield &hf = dem(a);
        const QuadTree tree(hf);
        const View view = views_of(hf)[0].view;
        const Retrieval full = retrieve(tree, view, {0.0, false});
        EXPECT_EQ(full.nodes.size(), std::size_t(hf.size())) << a.name;
        EXPECT_EQ(full.triangles.size(), 6u * (hf.width - 1) * (hf.height - 1)) << a.name;
        // From above the terrain every box is at a distance; a huge tolerance keeps the root.
        const Retrieval root = retrieve(tree, views_of(hf)[1].view, {1e12, false});
        EXPECT_EQ(root.nodes.size(), 5u) << a.name;
        EXPECT_EQ(root.triangles.size(), 12u) << a.name;
        EXPECT_EQ(root.tree_nodes, 1) << a.name;
    }
}

TEST(Retrieve, NodesShrinkAsToleranceGrowsAndEyeRises) {
    for (const Asset &a : dem_assets()) {
        const Heightfield &hf = dem(a);
        const QuadTree tree(hf);
        QuadTreeLod lod(tree);
        const View low = views_of(hf)[0].view;
        std::size_t prev = std::size_t(hf.size()) + 1;
        for (double tol : {0.0, 0.25, 0.5, 1.0, 2.0, 4.0, 16.0, 64.0, 1e6}) {
            const std::size_t n = lod.retrieve(low, {tol, false}).nodes.size();
            EXPECT_LE(n, prev) << a.name << " tol " << tol;
            prev = n;
        }
        prev = std::size_t(hf.size()) + 1;
        const double span = std::max((hf.width - 1) * hf.dx, (hf.height - 1) * hf.dy);
        for (double rise : {0.0, 0.01, 0.05, 0.2, 1.0, 5.0, 50.0}) {
            View v = low;
            v.eye.z = hf.max_z() + rise * span;
            const std::size_t n = lod.retrieve(v, {1.0, false}).nodes.size();
            EXPECT_LE(n, prev) << a.name << " rise " << rise;
            prev = n;
        }
    }
}

TEST(Retrieve, PeripheralWeightsBoundTheErasesWeightedErrorAtEverySample) {
    // With the screen model's peripheral factor the retrieval bounds the error the node erase
    // bounds: the screen error inside the frustum, relaxed by the factor outside it. Checked at
    // every sample: the erase's own exact measure of the retrieved TIN over all of them.
    const SignificanceOptions screen;
    for (const Asset &a : dem_assets()) {
        const Heightfield &hf = dem(a);
        const QuadTree tree(hf);
        for (const NamedView &nv : views_of(hf)) {
            const std::string what = a.name + " " + nv.name;
            RetrieveOptions ro;
            const Retrieval plain = retrieve(tree, nv.view, ro);
            ro.peripheral = &screen;
            const Retrieval weighed = retrieve(tree, nv.view, ro);
            EXPECT_LE(weighed.nodes.size(), plain.nodes.size()) << what;
            // From the low view, a tenth into the terrain, some of it lies behind the observer.
            if (nv.name == "low") {
                EXPECT_LT(weighed.nodes.size(), plain.nodes.size()) << what;
            }
            expect_crack_free(hf, weighed, what);
            ErrorOptions eo;
            eo.model = Significance::screen(nv.view);
            EXPECT_LE(measure_error(hf, weighed.triangles, eo).max_screen_px, 1.0 + 1e-9) << what;
            Mesh mesh = to_lattice_mesh(weighed, hf);
            const NodeEraser eraser(mesh, Significance::screen(nv.view, screen), EraseOptions{});
            const EraseStats bound = eraser.measure();
            // Within the tolerance, and within the bound the retrieval reports.
            EXPECT_LE(bound.max_weighted, 1.0 + 1e-6) << what;
            EXPECT_LE(bound.max_weighted, weighed.bound_px * (1.0 + 1e-6)) << what;
        }
    }
}

TEST(Retrieve, CullingKeepsTheBoundInsideTheFrustum) {
    for (const Asset &a : dem_assets()) {
        const Heightfield &hf = dem(a);
        const QuadTree tree(hf);
        for (const NamedView &nv : views_of(hf)) {
            const Retrieval all = retrieve(tree, nv.view, {1.0, false});
            const Retrieval culled = retrieve(tree, nv.view, {1.0, true});
            const std::string what = a.name + " " + nv.name;
            EXPECT_LE(culled.nodes.size(), all.nodes.size()) << what;
            ErrorOptions eo;
            eo.model = Significance::screen(nv.view);
            eo.frustum_only = true;
            const TinError err = measure_error(hf, culled.triangles, eo);
            EXPECT_EQ(err.uncovered, 0) << what;
            EXPECT_LE(err.max_screen_px, 1.0 + 1e-9) << what;
            expect_crack_free(hf, culled, what + " culled");
        }
    }
}

TEST(QuadTreeLod, StatusMatchesTheOutputAndResetsBetweenViews) {
    const Heightfield &hf = dem({"N42E001.hgt", {}});
    const QuadTree tree(hf);
    QuadTreeLod lod(tree);
    const auto views = views_of(hf);
    for (int pass = 0; pass < 2; ++pass)
        for (const NamedView &nv : views) {
            const Retrieval &r = lod.retrieve(nv.view, {1.0, false});
            const QuadLayout &lay = lod.layout();
            std::int64_t leaves = 0, reached = 0;
            for (int d = 0; d < lay.levels(); ++d)
                for (std::uint32_t j = 0; j < lay.y.count(d); ++j)
                    for (std::uint32_t i = 0; i < lay.x.count(d); ++i) {
                        const NodeStatus s = lod.status(d, i, j);
                        leaves += s == NodeStatus::leaf;
                        reached += s != NodeStatus::unread;
                        if (s != NodeStatus::unread && d > 0) {
                            ASSERT_EQ(lod.status(d - 1, lay.x.parent(d, i), lay.y.parent(d, j)),
                                      NodeStatus::subdivide);
                        }
                    }
            EXPECT_EQ(leaves, r.leaves) << nv.name;
            EXPECT_EQ(reached, r.tree_nodes) << nv.name;
            EXPECT_EQ(lod.status(0, 0, 0), NodeStatus::subdivide) << nv.name;
        }
}

TEST(Retrieve, MeshConversionKeepsProvenanceAndGeometry) {
    const Heightfield &hf = dem({"dem_srtm30.tif", {}});
    const QuadTree tree(hf);
    const View view = views_of(hf)[0].view;
    const Retrieval r = retrieve(tree, view, {1.0, false});
    Mesh mesh = to_mesh(r, tree.frame());
    EXPECT_EQ(mesh.n_vertices(), r.nodes.size());
    EXPECT_EQ(mesh.n_faces() * 3, r.triangles.size());
    const auto origin = get_origin_property(mesh);
    for (auto v : mesh.vertices()) {
        const auto id = mesh.property(origin, v);
        ASSERT_EQ(mesh.point(v)[2], hf.z[std::size_t(id)]);
        ASSERT_EQ(mesh.point(v)[0], float((id % hf.width) * hf.dx));
    }
    ErrorOptions eo;
    eo.model = Significance::screen(view);
    eo.frustum_only = false;
    EXPECT_LE(measure_error(hf, mesh, eo).max_screen_px, 1.0 + 1e-6);
}
