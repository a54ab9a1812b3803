// `tinlod tiles`: every tile within its level's error at every DEM sample, on a rough DEM whose
// coarse tiles the interior's strided lattice left over it (docs/tiles.md, "How a tile is made",
// step 6), measured by the npm decoder's checks (tests/tiles/check_tiles.mjs), not by the build's
// own measure; and the repaired tile built alone is the run's, whatever the budget or threads.
#include "assets.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include <sys/wait.h>

namespace fs = std::filesystem;
using tinlod::test::file_bytes;
using tinlod::test::run_cli;
using tinlod::test::temp_dir;

namespace {

// SRTM1 tile N44E007 (3601 x 3601 big-endian int16, rows from the north) of a rough terrain,
// 1,500 m +- 900 m in waves of a few kilometres with 10 m of noise: its level-6 tile 6/66/47
// holds the DEM's east and north edges, where the heights drop to the fill height between the
// interior's lines (every 4th post on level 6) and a rebuild left it at 1.14 of its bound.
std::string rough_hgt(const std::string &dir) {
    const std::string path = dir + "/N44E007.hgt";
    constexpr int n = 3601;
    std::string bytes;
    bytes.reserve(std::size_t(2 * n * n));
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
            const double x = (7.0 + c / 3600.0) * 1200.0, y = (45.0 - r / 3600.0) * 1200.0;
            const auto hash =
                std::uint32_t(std::llround(x) * 73856093LL ^ std::llround(y) * 19349663LL);
            const double h =
                1500.0 + 2.0 * (400.0 * std::sin(x / 90.0) * std::cos(y / 130.0) +
                                60.0 * std::sin(x / 13.0 + y / 17.0) + double(hash % 1000) / 200.0);
            const auto code = std::uint16_t(std::int16_t(std::lround(h)));
            bytes.push_back(char(code >> 8)), bytes.push_back(char(code & 255));
        }
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

const std::string k_tiles_dir = std::string(TINLOD_MESHES_DIR) + "/../tests/tiles";

// check_tiles.mjs's exit status and JSON report on the tile set `dir` of `dem`.
std::pair<int, nlohmann::json> npm_check(const std::string &dir, const std::string &dem) {
    const std::string report = dir + ".check.json";
    const int rc = std::system(("node '" + k_tiles_dir + "/check_tiles.mjs' '" + dir + "' '" + dem +
                                "' > '" + report + "'")
                                   .c_str());
    return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1,
            nlohmann::json::parse(file_bytes(report), nullptr, false)};
}

bool npm_decoder() {
    return fs::exists(k_tiles_dir + "/node_modules/@here/quantized-mesh-decoder") &&
           std::system("node --version > /dev/null 2>&1") == 0;
}

} // namespace

// Level 6 of the rough DEM: the decoder reads every sample of both tiles within the level's
// error, vertically and as CesiumJS draws them; the build's stats agree (no tile over, no warning).
TEST(TilesBound, RoughDemHasNoTileOverItsBoundAsTheDecoderMeasures) {
    if (!npm_decoder())
        GTEST_SKIP() << "node or @here/quantized-mesh-decoder missing (scripts/setup.sh)";
    const std::string dir = temp_dir(), dem = rough_hgt(dir), out = dir + "/set";
    const auto r = run_cli("tiles '" + dem + "' --min-zoom 6 --max-zoom 6 -o '" + out +
                           "' --stats '" + out + ".json'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    const auto [rc, report] = npm_check(out, dem);
    ASSERT_TRUE(report.is_object()) << "check_tiles.mjs printed no report";
    EXPECT_EQ(rc, 0) << report.dump(1);
    EXPECT_TRUE(report["failures"].empty()) << report["failures"].dump(1);
    EXPECT_EQ(report["tiles"].get<int>(), 2);
    EXPECT_GT(report["samples"].get<std::int64_t>(), 3600 * 3600);
    EXPECT_LE(report["worst_ratio"].get<double>(), 1.0);
    EXPECT_LE(report["worst_drawn_ratio"].get<double>(), 1.0);
    const auto stats = nlohmann::json::parse(file_bytes(out + ".json"));
    EXPECT_EQ(stats["error"]["tiles_over_bound"].get<int>(), 0);
    // The build's measure and the decoder's read the same worst sample.
    EXPECT_NEAR(
        stats["error"]["worst_ratio"].get<double>(),
        std::max(report["worst_ratio"].get<double>(), report["worst_drawn_ratio"].get<double>()),
        1e-3);
}

// The repaired tile, built alone (`--part`, one thread, through a 1 MiB budget: the DEM read by
// windows), is the run's byte for byte.
TEST(TilesBound, RepairedTileBuiltAloneIsTheRunsTile) {
    const std::string dir = temp_dir(), dem = rough_hgt(dir);
    const auto run = run_cli("--threads 2 tiles '" + dem + "' --min-zoom 6 --max-zoom 6 -o '" +
                             dir + "/run' --stats '" + dir + "/run.json'");
    ASSERT_EQ(run.status, 0) << run.err;
    const auto alone =
        run_cli("--threads 1 tiles '" + dem +
                "' --min-zoom 6 --max-zoom 6 --part 6/66/47 --memory-mb 1 -o '" + dir + "/alone'");
    ASSERT_EQ(alone.status, 0) << alone.err;
    const std::string tile = "/6/66/47.terrain";
    ASSERT_TRUE(fs::exists(dir + "/run" + tile));
    EXPECT_EQ(file_bytes(dir + "/alone" + tile), file_bytes(dir + "/run" + tile));
}
