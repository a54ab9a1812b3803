// Image error (OpenImageIO compare) on hand-made images with exact answers, image files in and
// out, and the sampled Hausdorff distance on hand-built meshes and the bunnies.
#include "assets.hpp"

#include "tinlod/error.hpp"
#include "tinlod/hausdorff.hpp"
#include "tinlod/image_metrics.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/render.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace tinlod;

namespace {

Image flat_image(int w, int h, std::uint8_t grey) {
    Image image;
    image.width = w;
    image.height = h;
    image.rgba.assign(std::size_t(w) * h * 4, grey);
    for (std::size_t i = 3; i < image.rgba.size(); i += 4)
        image.rgba[i] = 255;
    return image;
}

// Axis-aligned rectangle [0, w] x [0, h] at height z, two triangles.
Mesh rectangle(double w, double h, double z) {
    Mesh m;
    const auto a = m.add_vertex(Mesh::Point(0, 0, float(z)));
    const auto b = m.add_vertex(Mesh::Point(float(w), 0, float(z)));
    const auto c = m.add_vertex(Mesh::Point(float(w), float(h), float(z)));
    const auto d = m.add_vertex(Mesh::Point(0, float(h), float(z)));
    m.add_face(a, b, c);
    m.add_face(a, c, d);
    return m;
}

// Distance from p to triangle (a, b, c) the plain way: the plane when the foot falls inside,
// else the nearest of the three edge segments.
double brute_distance(const glm::dvec3 &p, const glm::dvec3 &a, const glm::dvec3 &b,
                      const glm::dvec3 &c) {
    const glm::dvec3 n = glm::cross(b - a, c - a);
    if (glm::length(n) > 0.0) {
        const glm::dvec3 u = glm::normalize(n);
        const glm::dvec3 foot = p - glm::dot(p - a, u) * u;
        const double s0 = glm::dot(glm::cross(b - a, foot - a), n);
        const double s1 = glm::dot(glm::cross(c - b, foot - b), n);
        const double s2 = glm::dot(glm::cross(a - c, foot - c), n);
        if (s0 >= 0 && s1 >= 0 && s2 >= 0)
            return std::abs(glm::dot(p - a, u));
    }
    auto segment = [&](const glm::dvec3 &s, const glm::dvec3 &t) {
        const double len2 = glm::dot(t - s, t - s);
        const double x = len2 > 0 ? std::clamp(glm::dot(p - s, t - s) / len2, 0.0, 1.0) : 0.0;
        return glm::length(p - (s + x * (t - s)));
    };
    return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

} // namespace

TEST(ImageMetrics, CountsDifferingPixelsMaxMeanAndPsnrExactly) {
    const int w = 40, h = 25;
    const Image a = flat_image(w, h, 100);
    Image b = a;
    for (int i = 0; i < 10; ++i)
        b.rgba[4 * std::size_t(i * 7)] += 3; // 10 pixels: red up 3 levels
    for (int i = 0; i < 5; ++i)
        b.rgba[4 * std::size_t(500 + i) + 1] += 2; // 5 pixels: green up 2 (not more than 2)
    b.rgba[4 * 900 + 3] = 0;                       // alpha is not compared
    const ImageDifference d = compare_images(a, b);
    const double values = 3.0 * w * h;
    EXPECT_EQ(d.differing_pixels, 10);
    EXPECT_DOUBLE_EQ(d.differing_share, 10.0 / (w * h));
    EXPECT_NEAR(d.max, 3.0, 1e-4);
    EXPECT_NEAR(d.mean, (10 * 3 + 5 * 2) / values, 1e-6);
    const double rms = std::sqrt((10 * 9 + 5 * 4) / values);
    EXPECT_NEAR(d.rms, rms, 1e-5);
    EXPECT_NEAR(d.psnr_db, 20.0 * std::log10(255.0 / rms), 1e-3);

    ImageCompareOptions strict;
    strict.threshold = 1.0;
    EXPECT_EQ(compare_images(a, b, strict).differing_pixels, 15);
}

TEST(ImageMetrics, IdenticalImagesHaveInfinitePsnr) {
    const Image a = flat_image(8, 8, 42);
    const ImageDifference d = compare_images(a, a);
    EXPECT_TRUE(std::isinf(d.psnr_db) && d.psnr_db > 0);
    EXPECT_EQ(d.differing_pixels, 0);
    EXPECT_EQ(d.max, 0.0);
    EXPECT_EQ(d.mean, 0.0);
}

TEST(ImageMetrics, DifferenceImageScalesAndClamps) {
    const Image a = flat_image(4, 4, 100);
    Image b = a;
    b.rgba[0] = 103; // +3 -> 24 at gain 8
    b.rgba[5] = 0;   // -100 -> clamped to 255
    const Image d = difference_image(a, b, 8.0);
    EXPECT_EQ(d.rgba[0], 24);
    EXPECT_EQ(d.rgba[5], 255);
    EXPECT_EQ(d.rgba[2], 0);
    EXPECT_EQ(d.rgba[3], 255);
}

TEST(ImageMetrics, SizeMismatchIsAnError) {
    EXPECT_THROW(compare_images(flat_image(4, 4, 0), flat_image(4, 5, 0)), Error);
    EXPECT_THROW(difference_image(flat_image(4, 4, 0), flat_image(5, 4, 0)), Error);
}

TEST(ImageFiles, PngRoundTripsAndBadPathsLeaveNoFile) {
    const std::string dir = test::temp_dir();
    Image a = flat_image(7, 3, 10);
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
        if (i % 4 != 3)
            a.rgba[i] = std::uint8_t(i * 37);
    write_image(dir + "/a.png", a);
    const Image b = read_image(dir + "/a.png");
    EXPECT_EQ(b.width, 7);
    EXPECT_EQ(b.height, 3);
    EXPECT_TRUE(a.rgba == b.rgba);
    EXPECT_THROW(write_image(dir + "/missing/a.png", a), Error);
    EXPECT_THROW(write_depth(dir + "/d.exr", a), Error); // no depth in it
    EXPECT_FALSE(std::filesystem::exists(dir + "/d.exr"));
    EXPECT_THROW(read_image(dir + "/nothing.png"), Error);
}

TEST(Hausdorff, ParallelRectanglesAreTheirSeparationApart) {
    const HausdorffResult r = hausdorff(rectangle(2, 1, 0), rectangle(2, 1, 0.5));
    EXPECT_NEAR(r.max, 0.5, 1e-6);
    EXPECT_NEAR(r.mean, 0.5, 1e-6);
    EXPECT_NEAR(r.max_a_to_b, 0.5, 1e-6);
    EXPECT_NEAR(r.max_b_to_a, 0.5, 1e-6);
}

TEST(Hausdorff, ScreenSpaceDistanceIsSeenFromWhereEachSampleLies) {
    // Looking straight down from 10 above the lower rectangle: its points are 0.5 from the upper
    // one, seen at no less than 10 away; the upper one's at no less than 9.5.
    View view;
    view.eye = {1.0, 0.5, 10.0};
    view.at = {1.0, 0.5, 0.0};
    HausdorffOptions options;
    options.model = Significance::screen(view);
    const HausdorffResult r = hausdorff(rectangle(2, 1, 0), rectangle(2, 1, 0.5), options);
    EXPECT_LE(r.max_screen_px_a_to_b, 0.5 * view.k() / 10.0 * (1.0 + 1e-12));
    EXPECT_NEAR(r.max_screen_px_a_to_b, 0.5 * view.k() / 10.0, 1e-4 * view.k());
    EXPECT_LE(r.max_screen_px_b_to_a, 0.5 * view.k() / 9.5 * (1.0 + 1e-12));
    EXPECT_NEAR(r.max_screen_px_b_to_a, 0.5 * view.k() / 9.5, 1e-4 * view.k());
    EXPECT_EQ(r.max_screen_px, r.max_screen_px_b_to_a);
    // Looking away, no sample is inside the frustum.
    view.at = {1.0, 0.5, 20.0};
    options.model = Significance::screen(view);
    EXPECT_EQ(hausdorff(rectangle(2, 1, 0), rectangle(2, 1, 0.5), options).max_screen_px, 0.0);
    // Without a view there is no screen measure.
    EXPECT_EQ(hausdorff(rectangle(2, 1, 0), rectangle(2, 1, 0.5)).max_screen_px, 0.0);
}

TEST(Hausdorff, SubsetIsOneSided) {
    // a = [0,1]x[0,1] lies inside b = [0,2]x[0,1]; b's far half is up to 1 away from a, and a
    // uniform point of b is on average 0.25 away.
    HausdorffOptions options;
    options.samples = 200000;
    const HausdorffResult r = hausdorff(rectangle(1, 1, 0), rectangle(2, 1, 0), options);
    EXPECT_LT(r.max_a_to_b, 1e-6);
    EXPECT_NEAR(r.max_b_to_a, 1.0, 1e-6); // b's corners are samples
    EXPECT_NEAR(r.mean_b_to_a, 0.25, 0.005);
    EXPECT_NEAR(r.max, 1.0, 1e-6);
}

TEST(Hausdorff, MeshAgainstItselfIsZeroAndSeedMakesItRepeatable) {
    const Mesh bunny = read_mesh(test::asset("bun_zipper_res4.ply"));
    HausdorffOptions options;
    options.samples = 20000;
    const HausdorffResult self = hausdorff(bunny, bunny, options);
    EXPECT_LT(self.max, 1e-7);
    const Mesh finer = read_mesh(test::asset("bun_zipper_res2.ply"));
    const HausdorffResult r1 = hausdorff(bunny, finer, options);
    const HausdorffResult r2 = hausdorff(bunny, finer, options);
    EXPECT_EQ(r1.max, r2.max);
    EXPECT_EQ(r1.mean, r2.mean);
    EXPECT_GT(r1.max, 0.0);
    EXPECT_GT(r1.max, r1.mean);
}

TEST(Hausdorff, VertexDistancesMatchBruteForce) {
    // With no face samples only the vertices are measured: compare the hierarchy's answer with a
    // scan of every triangle.
    const Mesh coarse = read_mesh(test::asset("bun_zipper_res4.ply"));
    const Mesh fine = read_mesh(test::asset("bun_zipper_res2.ply"));
    HausdorffOptions options;
    options.samples = 0;
    const HausdorffResult r = hausdorff(coarse, fine, options);
    std::vector<std::array<glm::dvec3, 3>> triangles;
    for (auto f : fine.faces()) {
        std::array<glm::dvec3, 3> t;
        int i = 0;
        for (auto v : f.vertices()) {
            const auto &q = fine.point(v);
            t[i++] = glm::dvec3(q[0], q[1], q[2]);
        }
        triangles.push_back(t);
    }
    double worst = 0, sum = 0;
    std::int64_t n = 0;
    for (auto v : coarse.vertices()) {
        if (v.faces().begin() == v.faces().end())
            continue;
        const auto &q = coarse.point(v);
        const glm::dvec3 p(q[0], q[1], q[2]);
        double best = INFINITY;
        for (const auto &t : triangles)
            best = std::min(best, brute_distance(p, t[0], t[1], t[2]));
        worst = std::max(worst, best);
        sum += best;
        ++n;
    }
    EXPECT_NEAR(r.max_a_to_b, worst, 1e-9);
    EXPECT_NEAR(r.mean_a_to_b, sum / double(n), 1e-9);
}
