// The colour legend of the scalar renders (issue #45 item 15): present in colour-mapped renders,
// absent in shaded ones, and its bar runs along the very colour map the mesh is drawn with.
#include "assets.hpp"

#include "tinlod/render.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <vector>

using namespace tinlod;
using tinlod::test::asset;

namespace {

using Rgb = std::array<int, 3>;

Rgb pixel(const Image &image, int x, int y) {
    const std::uint8_t *p = &image.rgba[4 * (std::size_t(y) * image.width + x)];
    return {p[0], p[1], p[2]};
}

int distance(const Rgb &a, const Rgb &b) {
    return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
}

// The unit square at z = 0 in two triangles, seen from straight above, lit from straight above
// (so a scalar colour is the colour map's own: 0.6 + 0.4 * lambert = 1).
Mesh unit_square() {
    Mesh mesh;
    const auto a = mesh.add_vertex({0, 0, 0}), b = mesh.add_vertex({1, 0, 0}),
               c = mesh.add_vertex({1, 1, 0}), d = mesh.add_vertex({0, 1, 0});
    mesh.add_face(a, b, c);
    mesh.add_face(a, c, d);
    return mesh;
}

View from_above() {
    View view;
    view.eye = {0.5, 0.5, 2.0};
    view.at = {0.5, 0.5, 0.0};
    view.viewport_w = 960; // tall enough for a bar of 270 rows, a colour a row
    view.viewport_h = 1080;
    return view;
}

RenderOptions scalar_options(float value, const std::string &legend) {
    RenderOptions options;
    options.color = ColorMode::face_scalar;
    options.face_scalar = {value, value};
    options.scalar_max = 10.0f;
    options.sun = {0.0f, 0.0f, 1.0f};
    options.legend = legend;
    return options;
}

} // namespace

TEST(RenderLegend, BarRunsAlongTheMeshColourMap) {
    REQUIRE_RENDER();
    Renderer renderer;
    const Mesh square = unit_square();
    const View view = from_above();
    const Image with = renderer.render(square, view, scalar_options(0.0f, "error (m)"));
    const Image without = renderer.render(square, view, scalar_options(0.0f, ""));
    // The legend is drawn in the top-right corner, and only there.
    int changed = 0;
    for (int y = 0; y < with.height; ++y)
        for (int x = 0; x < with.width; ++x)
            if (pixel(with, x, y) != pixel(without, x, y)) {
                ++changed;
                EXPECT_TRUE(x >= with.width / 2 && y < with.height / 2) << x << "," << y;
            }
    EXPECT_GT(changed, 1000);

    // The square drawn at value v (the map spans 0 to 10) has the colour of the bar where the
    // bar shows v: higher up for a larger v, evenly spaced for evenly spaced values.
    std::vector<double> rows;
    for (const float value : {1.0f, 3.0f, 5.0f, 7.0f, 9.0f}) {
        SCOPED_TRACE(value);
        const Image mesh = renderer.render(square, view, scalar_options(value, ""));
        const Rgb colour = pixel(mesh, mesh.width / 2, mesh.height / 2);
        // The legend pixels nearest that colour (the bar samples the map once a row).
        int nearest = 1 << 30;
        std::vector<std::pair<int, int>> found; // row, distance
        for (int y = 0; y < with.height / 2; ++y)
            for (int x = with.width / 2; x < with.width; ++x)
                if (pixel(with, x, y) != pixel(without, x, y)) {
                    const int d = distance(pixel(with, x, y), colour);
                    nearest = std::min(nearest, d);
                    found.emplace_back(y, d);
                }
        EXPECT_LE(nearest, 6) << "no legend pixel has the mesh's colour";
        double sum = 0;
        int n = 0;
        for (const auto &[y, d] : found)
            if (d <= nearest) {
                sum += y;
                ++n;
            }
        rows.push_back(sum / n);
    }
    for (std::size_t i = 1; i < rows.size(); ++i) {
        EXPECT_LT(rows[i], rows[i - 1]);
        const double step = rows[1] - rows[0];
        EXPECT_NEAR(rows[i] - rows[i - 1], step, 0.2 * std::abs(step));
    }
}

TEST(RenderLegend, OnlyColourMappedRendersCarryOne) {
    REQUIRE_RENDER();
    Renderer renderer;
    const Mesh square = unit_square();
    const View view = from_above();
    RenderOptions shade;
    shade.legend = "error (m)";
    const Image a = renderer.render(square, view, shade);
    shade.legend.clear();
    EXPECT_TRUE(a.rgba == renderer.render(square, view, shade).rgba);
    // A picture too small to hold the legend is left alone.
    View tiny = view;
    tiny.viewport_w = tiny.viewport_h = 64;
    EXPECT_TRUE(renderer.render(square, tiny, scalar_options(5.0f, "error (m)")).rgba ==
                renderer.render(square, tiny, scalar_options(5.0f, "")).rgba);
}

// A column of the top-right quarter where a run of pixels goes down the colour map (turbo) over
// at least half of its range: the legend's bar.
bool has_colour_bar(const Image &image) {
    std::vector<Rgb> map(256);
    for (int i = 0; i < 256; ++i) {
        const glm::vec3 c = turbo(float(i) / 255.0f);
        for (int k = 0; k < 3; ++k)
            map[i][k] = int(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
    }
    auto position = [&](const Rgb &c) { // index on the map, or -1 when off it
        int best = -1, best_d = 7;
        for (int i = 0; i < 256; ++i)
            if (const int d = distance(c, map[i]); d < best_d) {
                best = i;
                best_d = d;
            }
        return best;
    };
    for (int x = image.width / 2; x < image.width; ++x) {
        int top = -1, last = -1; // where the current run started on the map, where it is now
        for (int y = 0; y < image.height / 2; ++y) {
            const int at = position(pixel(image, x, y));
            if (at >= 0 && last >= 0 && at <= last + 2) { // down the map, up to rounding
                if (top - at >= 128)
                    return true;
            } else {
                top = at;
            }
            last = at;
        }
    }
    return false;
}

TEST(RenderLegend, CliColourMappedRenderHasTheBarAndShadeHasNot) {
    REQUIRE_RENDER();
    const std::string dir = test::temp_dir(), dem = asset("dem_squared.tif");
    const std::string camera = " --eye 1561,-1500,1500 --at 1561,1972,150 --viewport 480x270";
    for (const std::string color : {"sp", "shade"}) {
        SCOPED_TRACE(color);
        const std::string out = dir + "/" + color + ".png";
        const auto r = test::run_cli("render '" + dem + "'" + camera + " --color " + color +
                                     " --reference '" + dem + "' -o '" + out + "'");
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(has_colour_bar(read_image(out)), color != "shade");
    }
}
