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

} // namespace

TEST(TilesCesium, CesiumJsLoadsTheSrtmPyramidAndDrawsItsTerrain) {
    if (!fs::exists("/usr/bin/chromium"))
        GTEST_SKIP() << "no /usr/bin/chromium (Debian's chromium, which scripts/setup.sh installs)";
    if (!fs::exists(k_tiles_dir + "/node_modules/cesium") ||
        !fs::exists(k_tiles_dir + "/node_modules/puppeteer-core") ||
        std::system("node --version > /dev/null 2>&1") != 0)
        FAIL() << "tests/tiles has no node_modules: run scripts/setup.sh (npm ci there)";
    const std::string dir = temp_dir() + "/n42e001";
    const auto r = run_cli("tiles '" + asset("N42E001.hgt") + "' -o '" + dir + "' --normals");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string out = dir + ".cesium.json";
    const int rc = std::system(("node '" + k_tiles_dir + "/cesium_view.mjs' '" + dir + "' '" +
                                asset("N42E001.hgt") + "' > '" + out + "'")
                                   .c_str());
    std::ifstream in(out);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    nlohmann::json report;
    try {
        report = nlohmann::json::parse(text);
    } catch (const std::exception &) {
        FAIL() << "cesium_view.mjs printed no report: " << text;
    }
    EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << report.dump(1);
    EXPECT_TRUE(report["failures"].empty()) << report["failures"].dump(1);
    // The view reaches the levels whose error is a few hundred metres or less, and the heights
    // checked include some drawn there.
    EXPECT_GE(report["tile_levels"].back().get<int>(), 9) << report.dump();
    EXPECT_GE(report["height_samples"].get<int>(), 100) << report.dump();
    std::cout << "cesium: " << report.dump() << "\n";
}
