// The headless renderer on real DEMs: coverage of the frame predicted from the camera, shading,
// determinism, depth, and image error growing with coarsening; `tinlod render` and `compare`.
#include "assets.hpp"

#include "tinlod/error.hpp"
#include "tinlod/image_metrics.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/render.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace tinlod;
using tinlod::test::asset;
using tinlod::test::is_sky;

namespace {

const Heightfield &squared_dem() {
    static const Heightfield hf = load_heightfield(asset("dem_squared.tif"));
    return hf;
}

double sky_share(const Image &image, const RenderOptions &options) {
    std::size_t sky = 0, n = std::size_t(image.width) * image.height;
    for (std::size_t i = 0; i < n; ++i)
        sky += is_sky(image, i, options);
    return double(sky) / double(n);
}

// TIN over every `step`-th sample in both directions, spanning the same extent as the full grid.
Mesh subsampled_tin(const Heightfield &hf, int step) {
    EXPECT_EQ((hf.width - 1) % step, 0);
    EXPECT_EQ((hf.height - 1) % step, 0);
    std::vector<std::uint32_t> triangles;
    const auto id = [&](int c, int r) { return std::uint32_t(r * hf.width + c); };
    for (int r = 0; r + step < hf.height; r += step)
        for (int c = 0; c + step < hf.width; c += step) {
            triangles.insert(triangles.end(), {id(c, r), id(c + step, r), id(c + step, r + step)});
            triangles.insert(triangles.end(), {id(c, r), id(c + step, r + step), id(c, r + step)});
        }
    return tin_from_indices(hf, triangles);
}

View oblique_view(const Heightfield &hf, int w, int h) {
    const double ex = (hf.width - 1) * hf.dx, ey = (hf.height - 1) * hf.dy;
    View v;
    v.eye = {0.5 * ex, -0.4 * ey, hf.max_z() + 0.4 * ey};
    v.at = {0.5 * ex, 0.5 * ey, hf.min_z()};
    v.fov_deg = 50.0;
    v.viewport_w = w;
    v.viewport_h = h;
    return v;
}

} // namespace

TEST(Render, TopDownViewInsideTheTerrainLeavesNoSky) {
    REQUIRE_RENDER();
    const Heightfield &hf = squared_dem();
    const double ex = (hf.width - 1) * hf.dx, ey = (hf.height - 1) * hf.dy;
    View view;
    view.viewport_w = 400;
    view.viewport_h = 300;
    view.fov_deg = 60.0;
    // Half the ground footprint at distance D is D tan(30 deg) * (4/3, 1); keep it inside the
    // terrain with a 10% margin even where the ground is lowest.
    const double tan_half = std::tan(glm::radians(30.0));
    const double distance = 0.9 * std::min(0.5 * ex / (tan_half * 4.0 / 3.0), 0.5 * ey / tan_half);
    view.eye = {0.5 * ex, 0.5 * ey, hf.min_z() + distance};
    view.at = {0.5 * ex, 0.5 * ey, hf.min_z()};
    ASSERT_GT(view.eye.z, hf.max_z()) << "the eye must be above the terrain";
    RenderOptions options;
    options.depth = true;
    Renderer renderer;
    const Image image = renderer.render(grid_tin(hf), view, options);
    ASSERT_EQ(image.width, 400);
    ASSERT_EQ(image.height, 300);
    EXPECT_EQ(sky_share(image, options), 0.0);

    // Shading varies across real relief: standard deviation of luminance, grey levels.
    double sum = 0, sum2 = 0;
    const std::size_t n = std::size_t(image.width) * image.height;
    for (std::size_t i = 0; i < n; ++i) {
        const double y = 0.2126 * image.rgba[4 * i] + 0.7152 * image.rgba[4 * i + 1] +
                         0.0722 * image.rgba[4 * i + 2];
        sum += y;
        sum2 += y * y;
    }
    const double mean = sum / double(n);
    const double sd = std::sqrt(sum2 / double(n) - mean * mean);
    EXPECT_GT(sd, 8.0) << "mean luminance " << mean;
    std::printf("luminance mean %.1f, standard deviation %.1f\n", mean, sd);

    // Depth along the vertical axis is the eye height above the ground under each pixel.
    ASSERT_EQ(image.depth.size(), n);
    const double nearest = view.eye.z - hf.max_z() - 1e-3 * distance;
    const double farthest = view.eye.z - hf.min_z() + 1e-3 * distance;
    const auto [lo, hi] = std::minmax_element(image.depth.begin(), image.depth.end());
    EXPECT_GE(*lo, nearest);
    EXPECT_LE(*hi, farthest);
    EXPECT_GT(*hi - *lo, 0.5 * (hf.max_z() - hf.min_z())) << "depth follows the relief";
}

TEST(Render, DistantTopDownViewCoversThePredictedShare) {
    REQUIRE_RENDER();
    const Heightfield &hf = squared_dem();
    const double ex = (hf.width - 1) * hf.dx, ey = (hf.height - 1) * hf.dy;
    View view;
    view.viewport_w = 320;
    view.viewport_h = 320;
    view.fov_deg = 40.0;
    view.eye = {0.5 * ex, 0.5 * ey, hf.max_z() + 2.5 * ey};
    view.at = {0.5 * ex, 0.5 * ey, 0.0};
    // The footprint is ex x ey seen at a distance between eye - max_z and eye - min_z.
    const double k = view.k();
    const double pixels = double(view.viewport_w) * view.viewport_h;
    const double largest = ex * ey * k * k / std::pow(view.eye.z - hf.max_z(), 2) / pixels;
    const double smallest = ex * ey * k * k / std::pow(view.eye.z - hf.min_z(), 2) / pixels;
    ASSERT_LT(largest, 0.9) << "the terrain must lie inside the frame";
    RenderOptions options;
    Renderer renderer;
    const double terrain = 1.0 - sky_share(renderer.render(grid_tin(hf), view, options), options);
    const double edge = 2.0 * (ex + ey) * k / (view.eye.z - hf.max_z()) / pixels; // one pixel ring
    std::printf("terrain share %.4f, predicted [%.4f, %.4f] +- %.4f\n", terrain, smallest, largest,
                edge);
    EXPECT_GE(terrain, smallest - edge);
    EXPECT_LE(terrain, largest + edge);
}

TEST(Render, HorizontalViewHasSkyAboveTheHorizonAndGroundBelow) {
    REQUIRE_RENDER();
    const Heightfield &hf = squared_dem();
    const double ex = (hf.width - 1) * hf.dx, ey = (hf.height - 1) * hf.dy;
    View view;
    view.viewport_w = 320;
    view.viewport_h = 240;
    view.fov_deg = 60.0;
    // Eye above the highest sample, looking level: nothing rises above the horizon line.
    const double eye_z = hf.max_z() + 80.0;
    view.eye = {0.5 * ex, -200.0, eye_z};
    view.at = {0.5 * ex, ey, eye_z};
    // The bottom row descends tan(30 deg) per unit forward: it reaches the lowest sample height
    // well inside the terrain, so it must hit ground.
    const double reach = (eye_z - hf.min_z()) / std::tan(glm::radians(30.0)) - 200.0;
    ASSERT_LT(reach, ey);
    RenderOptions options;
    options.color = ColorMode::height;
    Renderer renderer;
    const Image image = renderer.render(grid_tin(hf), view, options);
    std::size_t upper_sky = 0, bottom_ground = 0;
    for (int r = 0; r < image.height / 2; ++r)
        for (int c = 0; c < image.width; ++c)
            upper_sky += is_sky(image, std::size_t(r) * image.width + c, options);
    for (int c = 0; c < image.width; ++c)
        bottom_ground += !is_sky(image, std::size_t(image.height - 1) * image.width + c, options);
    EXPECT_EQ(upper_sky, std::size_t(image.width) * (image.height / 2));
    EXPECT_EQ(bottom_ground, std::size_t(image.width));
    EXPECT_LT(sky_share(image, options), 0.9);
}

TEST(Render, SameInputGivesIdenticalBytesAndInfinitePsnr) {
    REQUIRE_RENDER();
    const Heightfield &hf = squared_dem();
    const Mesh tin = grid_tin(hf);
    const View view = oblique_view(hf, 480, 270);
    RenderOptions options;
    options.wire = true;
    Image first, second;
    {
        Renderer renderer;
        first = renderer.render(tin, view, options);
        second = renderer.render(tin, view, options);
    }
    Renderer fresh;
    const Image third = fresh.render(tin, view, options);
    EXPECT_TRUE(first.rgba == second.rgba);
    EXPECT_TRUE(first.rgba == third.rgba);
    const ImageDifference d = compare_images(first, third);
    EXPECT_TRUE(std::isinf(d.psnr_db) && d.psnr_db > 0);
    EXPECT_EQ(d.differing_pixels, 0);
    EXPECT_EQ(d.max, 0.0);
}

TEST(Render, CoarserTinsShowLargerImageAndGeometricError) {
    REQUIRE_RENDER();
    const Heightfield &hf = squared_dem();
    const View view = oblique_view(hf, 640, 360);
    RenderOptions options;
    options.z_min = hf.min_z();
    options.z_max = hf.max_z();
    options.color = ColorMode::height;
    const Mesh full = grid_tin(hf);
    options.clip = clip_range(full, view);
    RenderOptions dem_shaded = options;
    dem_shaded.normal_source = &hf;
    Renderer renderer;
    const Image truth = renderer.render(full, view, options);
    const Image dem_truth = renderer.render(full, view, dem_shaded);
    double last_psnr = INFINITY, last_share = 0.0, last_vertical = 0.0, last_screen = 0.0;
    double last_dem_psnr = INFINITY;
    for (int step : {2, 4, 8, 16}) {
        const Mesh coarse = subsampled_tin(hf, step);
        const ImageDifference d = compare_images(renderer.render(coarse, view, options), truth);
        const ImageDifference dd =
            compare_images(renderer.render(coarse, view, dem_shaded), dem_truth);
        ErrorOptions eo;
        eo.model = Significance::screen(view);
        const TinError e = measure_error(hf, coarse, eo);
        SCOPED_TRACE("step " + std::to_string(step));
        std::printf("step %2d: PSNR %.2f dB, %.3f%% pixels > 2 levels, max %.0f; with DEM normals "
                    "%.2f dB, %.3f%%; vertical max %.2f, screen max %.2f px\n",
                    step, d.psnr_db, 100.0 * d.differing_share, d.max, dd.psnr_db,
                    100.0 * dd.differing_share, e.max_vertical, e.max_screen_px);
        EXPECT_LT(d.psnr_db, last_psnr);
        EXPECT_GT(d.differing_share, last_share);
        EXPECT_GT(e.max_vertical, last_vertical);
        EXPECT_GT(e.max_screen_px, last_screen);
        EXPECT_LT(dd.psnr_db, last_dem_psnr);
        // Shading by the DEM's normals leaves only the surface's movement on screen.
        EXPECT_GT(dd.psnr_db, d.psnr_db);
        EXPECT_LT(dd.differing_share, d.differing_share);
        last_psnr = d.psnr_db;
        last_share = d.differing_share;
        last_vertical = e.max_vertical;
        last_screen = e.max_screen_px;
        last_dem_psnr = dd.psnr_db;
    }
    // At one sample in 16 the relief is plainly different: far from the reference.
    EXPECT_LT(last_psnr, 30.0);
    EXPECT_GT(last_share, 0.05);
}

TEST(Render, LargeRealDemRendersWithWireAndScalars) {
    REQUIRE_RENDER();
    const Heightfield hf = load_heightfield(asset("N42E001.hgt"));
    const Mesh tin = grid_tin(hf);
    const View view = oblique_view(hf, 320, 180);
    Renderer renderer;
    RenderOptions options;
    const Image shade = renderer.render(tin, view, options);
    options.wire = true;
    const Image wire = renderer.render(tin, view, options);
    // 2.9 M triangles in 320x180 pixels: the wire darkens most of the terrain.
    double shade_sum = 0, wire_sum = 0;
    for (std::size_t i = 0; i < shade.rgba.size(); i += 4) {
        shade_sum += shade.rgba[i + 1];
        wire_sum += wire.rgba[i + 1];
    }
    EXPECT_LT(wire_sum, 0.9 * shade_sum);
    std::printf("wire / shade green sum: %.3f\n", wire_sum / shade_sum);

    options.wire = false;
    options.color = ColorMode::face_scalar;
    options.face_scalar.assign(tin.n_faces(), 1.0f);
    options.face_scalar.front() = 0.0f; // the map spans [0, 1]: every other face at its top colour
    const Image faces = renderer.render(tin, view, options);
    EXPECT_FALSE(faces.rgba == shade.rgba);
    options.face_scalar.pop_back();
    EXPECT_THROW(renderer.render(tin, view, options), Error);
}

TEST(RenderCli, RenderAndCompareOnARealDem) {
    REQUIRE_RENDER();
    const std::string dir = test::temp_dir();
    const std::string dem = asset("dem_squared.tif");
    const std::string camera = " --eye 1561,-1500,1500 --at 1561,1972,150 --viewport 320x180";
    auto r = test::run_cli("render '" + dem + "'" + camera + " --color error --reference '" + dem +
                           "' --wire -o '" + dir + "/a.png' --depth '" + dir + "/a.exr'");
    ASSERT_EQ(r.status, 0) << r.err;
    const Image a = read_image(dir + "/a.png");
    EXPECT_EQ(a.width, 320);
    EXPECT_EQ(a.height, 180);
    EXPECT_TRUE(std::filesystem::file_size(dir + "/a.exr") > 0);

    r = test::run_cli("compare '" + dem + "' '" + dem + "'" + camera + " --json --diff '" + dir +
                      "/d.png'");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_TRUE(j["image"]["psnr_db"].is_null());
    EXPECT_TRUE(j["image"]["identical"].get<bool>());
    EXPECT_EQ(j["image"]["differing_pixels"].get<long long>(), 0);
    EXPECT_EQ(j["geometry"]["max_vertical"].get<double>(), 0.0);
    const Image diff = read_image(dir + "/d.png");
    for (std::size_t i = 0; i < diff.rgba.size(); i += 4)
        ASSERT_EQ(diff.rgba[i] + diff.rgba[i + 1] + diff.rgba[i + 2], 0);
}

TEST(RenderCli, CompareMeshesByHausdorffAndImage) {
    REQUIRE_RENDER();
    const std::string coarse = asset("bun_zipper_res4.ply"), fine = asset("bun_zipper_res2.ply");
    const auto r = test::run_cli("compare '" + coarse + "' '" + fine +
                                 "' --eye -0.02,0.11,0.35 --at -0.02,0.11,0 --viewport 320x240 "
                                 "--samples 20000 --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const auto &g = j["geometry"];
    // The bunny is about 0.15 across; res4 keeps its shape within a few percent of that.
    EXPECT_GT(g["hausdorff_max"].get<double>(), 0.0);
    EXPECT_LT(g["hausdorff_max"].get<double>(), 0.02);
    EXPECT_LT(g["hausdorff_mean"].get<double>(), g["hausdorff_max"].get<double>());
    EXPECT_FALSE(j["image"]["identical"].get<bool>());
    EXPECT_GT(j["image"]["differing_share"].get<double>(), 0.0);
}

// simplify on a surface mesh bounds every input vertex's screen-space distance to the output
// surface; compare, measuring only the vertices (--samples 0), finds the same bound.
TEST(RenderCli, SimplifiedMeshKeepsEveryReferenceVertexWithinTheBound) {
    REQUIRE_RENDER();
    const std::string dir = test::temp_dir(), fine = asset("bun_zipper_res2.ply");
    // From the front, 2.5 bounding radii away (bench/ sees the bunny so).
    const std::string camera = " --eye 0.0207,0.1602,0.3112 --at -0.01685,0.11015,-0.00155";
    auto r = test::run_cli("simplify '" + fine + "'" + camera + " --tol 1 -o '" + dir + "/s.ply'");
    ASSERT_EQ(r.status, 0) << r.err;
    r = test::run_cli("compare '" + dir + "/s.ply' '" + fine + "'" + camera +
                      " --samples 0 --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto g = nlohmann::json::parse(r.out)["geometry"];
    EXPECT_LE(g["max_screen_px_reference_to_mesh"].get<double>(), 1.0 + 1e-9);
    EXPECT_GT(g["max_screen_px_reference_to_mesh"].get<double>(), 0.5);
    EXPECT_EQ(g["max_screen_px_mesh_to_reference"].get<double>(), 0.0); // its vertices are the
                                                                        // reference's
}

TEST(RenderCli, BadRequestsFailWithOneLineAndNoFile) {
    const std::string dir = test::temp_dir();
    const std::string bunny = asset("bun_zipper_res4.ply");
    auto r = test::run_cli("render '" + bunny + "' --eye 0,0,1 --at 0,0,0 --color error -o '" +
                           dir + "/x.png'");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("--color error"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
    r = test::run_cli("render '" + bunny + "' --eye 0,0,1 --at 0,0,1 -o '" + dir + "/x.png'");
    EXPECT_NE(r.status, 0);
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
}
