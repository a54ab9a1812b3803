// `tinlod tiles` read by a real client: CesiumJS (npm `cesium`) in headless Chromium (Debian's
// `chromium`, driven by npm `puppeteer-core`) loads the bundled SRTM tile's pyramid from a server
// on 127.0.0.1 (tests/tiles/cesium_view.mjs): no tile error, no request for a tile the set lacks,
// nothing fetched from elsewhere, a picture that is not the bare ellipsoid's and heights within the
// drawing level's error.
#include "assets.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include <sys/wait.h>

namespace fs = std::filesystem;
using tinlod::test::asset;
using tinlod::test::run_cli;
using tinlod::test::temp_dir;

namespace {

const std::string k_tiles_dir = std::string(TINLOD_MESHES_DIR) + "/../tests/tiles";

bool npm_installed() {
    return fs::exists(k_tiles_dir + "/node_modules/@here/quantized-mesh-decoder") &&
           fs::exists(k_tiles_dir + "/node_modules/cesium") &&
           fs::exists(k_tiles_dir + "/node_modules/puppeteer-core") &&
           std::system("node --version > /dev/null 2>&1") == 0;
}

// Runs a script of tests/tiles with `args` (shell-quoted); its exit status and its JSON report.
std::pair<int, nlohmann::json> run_node(const std::string &script, const std::string &args,
                                        const std::string &out) {
    const int rc = std::system(
        ("node '" + k_tiles_dir + "/" + script + "' " + args + " > '" + out + "'").c_str());
    std::ifstream in(out);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    nlohmann::json report;
    try {
        report = nlohmann::json::parse(text);
    } catch (const std::exception &) {
        report = {{"failures", {script + " printed no report: " + text}}};
    }
    return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, report};
}

} // namespace

// CesiumJS asks for both level-0 tiles and has no parent to upsample a missing one from: without
// 0/0/0 it drew nothing west of Greenwich. And it draws a triangle flat between its vertices'
// Earth-centred positions: the few triangles of a coarse tile over fill once cut thousands of
// kilometres under the surface. The npm decoder's checks measure that gap on every triangle.
TEST(TilesCesium, LevelZeroIsWrittenWholeAndTrianglesDrawnFlatStayNearTheSurface) {
    if (!npm_installed())
        FAIL() << "tests/tiles has no node_modules: run scripts/setup.sh (npm ci there)";
    const std::string dir = temp_dir() + "/n42e001";
    const auto r = run_cli("tiles '" + asset("N42E001.hgt") + "' -o '" + dir + "' --max-zoom 6");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir + "/0/0/0.terrain"));
    std::ifstream layer_in(dir + "/layer.json");
    const auto layer = nlohmann::json::parse(layer_in);
    EXPECT_EQ(layer["available"][0],
              nlohmann::json::parse(R"([{"startX": 0, "startY": 0, "endX": 1, "endY": 0}])"));
    const auto [rc, report] =
        run_node("check_tiles.mjs", "'" + dir + "' '" + asset("N42E001.hgt") + "'", dir + ".json");
    EXPECT_EQ(rc, 0) << report.dump();
    EXPECT_TRUE(report["failures"].empty()) << report["failures"].dump(1);
    EXPECT_LE(report["worst_chord_ratio"].get<double>(), 1.0 / 16.0) << report.dump();
}

TEST(TilesCesium, CesiumJsLoadsTheSrtmPyramidAndDrawsItsTerrain) {
    if (!fs::exists("/usr/bin/chromium"))
        GTEST_SKIP() << "no /usr/bin/chromium (Debian's chromium, which scripts/setup.sh installs)";
    if (!npm_installed())
        FAIL() << "tests/tiles has no node_modules: run scripts/setup.sh (npm ci there)";
    const std::string dir = temp_dir() + "/n42e001";
    const auto r = run_cli("tiles '" + asset("N42E001.hgt") + "' -o '" + dir + "' --normals");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto [rc, report] = run_node(
        "cesium_view.mjs", "'" + dir + "' '" + asset("N42E001.hgt") + "'", dir + ".cesium.json");
    EXPECT_EQ(rc, 0) << report.dump(1);
    EXPECT_TRUE(report["failures"].empty()) << report["failures"].dump(1);
    // The view reaches the levels whose error is a few hundred metres or less, and the heights
    // checked include some drawn there.
    ASSERT_TRUE(report.contains("tile_levels")) << report.dump();
    EXPECT_GE(report["tile_levels"].back().get<int>(), 9) << report.dump();
    EXPECT_GE(report["height_samples"].get<int>(), 100) << report.dump();
    std::cout << "cesium: " << report.dump() << "\n";
}
