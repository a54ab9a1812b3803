// The significance parameter (lib/significance) and the focal point (lib/focal): SP falls with
// distance and with the observation angle in both models; the focal point lies on the surface
// and on the axis, with a defined fallback when the axis misses.
#include "assets.hpp"

#include "tinlod/focal.hpp"
#include "tinlod/significance.hpp"

#include "tinlod/screen_weight.hpp"

#include <gtest/gtest.h>

#include <random>

namespace tinlod {
namespace {

View looking_north() {
    View v;
    v.eye = {0.0, 0.0, 100.0};
    v.at = {0.0, 1000.0, 0.0};
    return v;
}

TEST(Significance, FallsWithDistance) {
    const View view = looking_north();
    for (SpModel model : {SpModel::screen, SpModel::paper}) {
        SignificanceOptions options;
        options.model = model;
        NodeTerms near{100.0, 0.1, 2.0, 0.1, 1.0}, far = near;
        far.od = 1000.0;
        EXPECT_GT(significance(near, &view, options, 500.0),
                  significance(far, &view, options, 500.0));
    }
}

TEST(Significance, FallsWithObservationAngle) {
    const View view = looking_north();
    SignificanceOptions options;
    // Same distance, one point on the axis, one behind the observer's shoulder.
    const glm::dvec3 ahead = view.eye + 500.0 * view.axis();
    const glm::dvec3 aside = view.eye + 500.0 * glm::dvec3(1.0, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(peripheral_factor(view, ahead, options), 1.0);
    EXPECT_LT(peripheral_factor(view, aside, options), 1.0);
    EXPECT_GE(peripheral_factor(view, aside, options), options.floor);
    EXPECT_GT(screen_weight(view, ahead, options), screen_weight(view, aside, options));
    EXPECT_GT(observation_angle(view, aside), observation_angle(view, ahead));

    options.model = SpModel::paper;
    NodeTerms on_axis{500.0, 0.0, 2.0, 0.1, 1.0}, off_axis = on_axis;
    off_axis.oa = 1.2;
    EXPECT_GT(significance(on_axis, &view, options, 500.0),
              significance(off_axis, &view, options, 500.0));
}

TEST(Significance, ScreenModelIsPixelsOfDeviation) {
    const View view = looking_north();
    SignificanceOptions options;
    const NodeTerms t{250.0, 0.0, 3.0, 0.0, 1.0};
    EXPECT_NEAR(significance(t, &view, options), 3.0 * view.k() / 250.0, 1e-9);
    options.model = SpModel::vertical;
    EXPECT_DOUBLE_EQ(significance(t, nullptr, options), 3.0);
}

TEST(Significance, NodeSignificanceOnARealTinFallsFarAway) {
    const Heightfield hf = load_heightfield(test::asset("dem_squared.tif"));
    const Mesh tin = grid_tin(hf);
    const double w = (hf.width - 1) * hf.dx;
    View near;
    near.eye = {0.5 * w, 0.5 * w, hf.max_z() + 0.2 * w};
    near.at = {0.5 * w, 0.5 * w, hf.min_z()};
    View far = near;
    far.eye.z += 5.0 * w;
    SignificanceOptions options;
    const auto sp_near = node_significance(tin, &near, options);
    const auto sp_far = node_significance(tin, &far, options);
    std::int64_t interior = 0, lower = 0;
    for (auto v : tin.vertices()) {
        if (tin.is_boundary(v) || sp_near[v.idx()] == 0.0f)
            continue;
        ++interior;
        lower += sp_far[v.idx()] < sp_near[v.idx()];
    }
    ASSERT_GT(interior, 1000);
    EXPECT_EQ(lower, interior);
}

// The Weigher (lib/include/tinlod/screen_weight.hpp) computes the screen model's weight k / OD *
// peripheral(OA) for the erase and the retrieval, and bounds it over boxes: the erase skips nodes,
// and the retrieval leaves nodes unsplit, on those bounds. Random boxes around views of every kind,
// and points in each (corners, and points pulled toward the frustum's margin band and the cone's
// edge, where the factor steps and the shortcuts by cosines decide).
TEST(Weigher, MatchesScreenWeightAndBoundsItOverEveryBox) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const SignificanceOptions options;
    std::vector<View> views;
    views.push_back(looking_north());
    View down; // straight down
    down.eye = {0.0, 0.0, 5000.0};
    down.at = {0.0, 0.0, 0.0};
    views.push_back(down);
    View narrow; // oblique, narrow lens, square viewport
    narrow.eye = {100.0, -300.0, 800.0};
    narrow.at = {-200.0, 900.0, 0.0};
    narrow.fov_deg = 20.0;
    narrow.viewport_w = narrow.viewport_h = 512;
    views.push_back(narrow);
    for (const View &view : views) {
        const Weigher weigher(&view, options);
        const glm::dvec3 f = view.axis();
        // A point at distance r whose direction makes angle a with the axis, at azimuth b.
        const glm::dvec3 side = glm::normalize(
            glm::cross(f, std::abs(f.z) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1)));
        const glm::dvec3 up = glm::cross(side, f);
        const double cone = std::atan(
            0.5 * std::hypot(double(view.viewport_w), double(view.viewport_h)) / view.k());
        auto around = [&](double r, double a, double b) {
            return view.eye +
                   r * (std::cos(a) * f + std::sin(a) * (std::cos(b) * side + std::sin(b) * up));
        };
        int boxes = 0;
        for (int k = 0; k < 4000; ++k) {
            // Centres at any angle, most near the cone's edge; sizes from a metre to kilometres.
            const double a = unit(rng) < 0.6 ? cone + 0.05 * (unit(rng) - 0.5) : M_PI * unit(rng);
            const glm::dvec3 c = around(50.0 + 5000.0 * unit(rng), a, 2.0 * M_PI * unit(rng));
            const glm::dvec3 half =
                glm::dvec3(unit(rng), unit(rng), unit(rng)) * std::pow(10.0, 3.5 * unit(rng));
            const glm::dvec3 lo = c - half, hi = c + half;
            if (glm::all(glm::lessThanEqual(lo, view.eye)) &&
                glm::all(glm::lessThanEqual(view.eye, hi)))
                continue; // the eye inside: the bound is infinite
            ++boxes;
            const double upper = weigher.bound(lo, hi), lower = weigher.lower(lo, hi);
            for (int j = 0; j < 40; ++j) {
                glm::dvec3 p;
                if (j < 8)
                    p = {j & 1 ? hi.x : lo.x, j & 2 ? hi.y : lo.y, j & 4 ? hi.z : lo.z};
                else
                    p = lo + glm::dvec3(unit(rng), unit(rng), unit(rng)) * (hi - lo);
                const double w = weigher(p);
                ASSERT_NEAR(w, screen_weight(view, p, options), 1e-9 * w);
                ASSERT_GE(upper, w * (1.0 - 1e-12)) << "box " << k << ", point " << j;
                ASSERT_LE(lower, w * (1.0 + 1e-12)) << "box " << k << ", point " << j;
            }
        }
        EXPECT_GT(boxes, 3000);
        // The frustum's margin band at its corners lies outside the cone through the viewport's
        // corners, and the factor there is 1: small boxes around such points.
        const double m = 0.9 * options.cone_margin_px;
        for (const double sx : {-1.0, 1.0})
            for (const double sy : {-1.0, 1.0})
                for (const double r : {100.0, 1000.0, 10000.0}) {
                    const glm::dvec3 d = f + sx * (view.viewport_w / 2.0 + m) / view.k() * side +
                                         sy * (view.viewport_h / 2.0 + m) / view.k() * up;
                    const glm::dvec3 p = view.eye + r * glm::normalize(d);
                    ASSERT_GT(observation_angle(view, p), cone);
                    const double w = weigher(p);
                    ASSERT_NEAR(w, view.k() / r, 1e-9 * w); // in the frustum's margin: factor 1
                    const glm::dvec3 half(1e-6 * r);
                    ASSERT_GE(weigher.bound(p - half, p + half), w * (1.0 - 1e-12));
                    ASSERT_LE(weigher.lower(p - half, p + half), w * (1.0 + 1e-12));
                }
    }
}

TEST(Focal, HitsTheSurfaceOnTheAxis) {
    const Heightfield hf = load_heightfield(test::asset("dem_srtm30.tif"));
    const Mesh tin = grid_tin(hf);
    const FocalIndex index(tin);
    const double w = (hf.width - 1) * hf.dx, h = (hf.height - 1) * hf.dy;
    for (const glm::dvec3 at :
         {glm::dvec3(0.5 * w, 0.5 * h, hf.min_z()), glm::dvec3(0.2 * w, 0.8 * h, hf.min_z()),
          glm::dvec3(0.9 * w, 0.1 * h, hf.min_z())}) {
        View view;
        view.eye = {-0.1 * w, -0.1 * h, hf.max_z() + 0.3 * w};
        view.at = at;
        const FocalPoint f = index.cast(view);
        ASSERT_TRUE(f.hit);
        // On the axis ...
        const glm::dvec3 off_axis = glm::cross(f.point - view.eye, view.axis());
        EXPECT_LT(glm::length(off_axis), 1e-6 * f.distance);
        // ... and on the surface: its height is the TIN's under it (bilinear bounds of the cell).
        const int c = int(f.point.x / hf.dx), r = int(f.point.y / hf.dy);
        const float lo =
            std::min({hf.at(c, r), hf.at(c + 1, r), hf.at(c, r + 1), hf.at(c + 1, r + 1)});
        const float hi =
            std::max({hf.at(c, r), hf.at(c + 1, r), hf.at(c, r + 1), hf.at(c + 1, r + 1)});
        EXPECT_GE(f.point.z, lo - 1e-3);
        EXPECT_LE(f.point.z, hi + 1e-3);
        // The first hit: every sample on the way lies below the ray.
        for (double t = 0.0; t < f.distance * 0.99; t += f.distance / 200) {
            const glm::dvec3 p = view.eye + t * view.axis();
            const int pc = int(std::floor(p.x / hf.dx)), pr = int(std::floor(p.y / hf.dy));
            if (pc < 0 || pr < 0 || pc >= hf.width || pr >= hf.height)
                continue;
            EXPECT_GT(p.z, hf.at(pc, pr) - 100.0);
        }
    }
}

TEST(Focal, FallsBackWhenTheAxisMisses) {
    const Heightfield hf = load_heightfield(test::asset("dem_squared.tif"));
    const Mesh tin = grid_tin(hf);
    View up; // looking up into the sky
    up.eye = {10.0, 10.0, hf.max_z() + 10.0};
    up.at = {10.0, 20.0, hf.max_z() + 100.0};
    const FocalPoint sky = focal_point(tin, up);
    EXPECT_FALSE(sky.hit);
    EXPECT_EQ(sky.point, up.at);
    View past; // looking down but away from the terrain
    past.eye = {-1000.0, -1000.0, hf.max_z() + 10.0};
    past.at = {-2000.0, -2000.0, hf.min_z()};
    const FocalPoint beside = focal_point(tin, past);
    EXPECT_FALSE(beside.hit);
    EXPECT_GT(beside.distance, 0.0);
    EXPECT_LT(glm::length(glm::cross(beside.point - past.eye, past.axis())),
              1e-6 * beside.distance);
}

} // namespace
} // namespace tinlod
