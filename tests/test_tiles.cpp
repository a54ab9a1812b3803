// `tinlod tiles`: the quantized-mesh pyramid of the bundled SRTM tile, read back by a decoder from
// npm (tests/tiles/check_tiles.mjs, @here/quantized-mesh-decoder) that checks the format, the
// shared edges and the error at every DEM sample; a tile built alone against the same tile of the
// whole run; other coverages; and bad input.
#include "assets.hpp"

#include "tinlod/tiles.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace tinlod;
using tinlod::test::asset;
using tinlod::test::file_bytes;
using tinlod::test::run_cli;
using tinlod::test::temp_dir;

namespace {

// `path` in single quotes for the shell (appended piece by piece: GCC 12 warns, -Wrestrict, a
// false positive, on the inlined `"'" + std::string`).
std::string quoted(const std::string &path) {
    std::string q = "'";
    q += path;
    q += "'";
    return q;
}

// Runs the npm decoder's checks on a tile set; returns its exit status and its JSON report.
std::pair<int, nlohmann::json> check_tiles(const std::string &dir, const std::string &dems) {
    const std::string script = std::string(TINLOD_MESHES_DIR) + "/../tests/tiles/check_tiles.mjs";
    const std::string out = dir + ".check.json";
    const int rc =
        std::system(("node '" + script + "' '" + dir + "' " + dems + " > '" + out + "'").c_str());
    nlohmann::json report;
    try {
        report = nlohmann::json::parse(file_bytes(out));
    } catch (const std::exception &) {
    }
    return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, report};
}

bool decoder_installed() {
    return fs::exists(std::string(TINLOD_MESHES_DIR) +
                      "/../tests/tiles/node_modules/@here/quantized-mesh-decoder") &&
           std::system("node --version > /dev/null 2>&1") == 0;
}

std::string gunzip(const std::string &bytes) {
    z_stream s{};
    inflateInit2(&s, 15 + 16);
    std::string out(1 << 20, '\0');
    s.next_in = reinterpret_cast<Bytef *>(const_cast<char *>(bytes.data()));
    s.avail_in = uInt(bytes.size());
    s.next_out = reinterpret_cast<Bytef *>(out.data());
    s.avail_out = uInt(out.size());
    inflate(&s, Z_FINISH);
    out.resize(s.total_out);
    inflateEnd(&s);
    return out;
}

// The header's minimum and maximum heights (floats at bytes 24 and 28 of the quantized mesh).
std::pair<float, float> header_heights(const std::string &gz_file) {
    const std::string raw = gunzip(file_bytes(gz_file));
    float h[2] = {NAN, NAN};
    if (raw.size() >= 32)
        std::memcpy(h, raw.data() + 24, sizeof h);
    return {h[0], h[1]};
}

// The bad-input contract: one line naming the subject, the status, and no tile set left.
void expect_refused(const test::RunResult &r, int status, const std::string &subject,
                    const std::string &dir) {
    EXPECT_EQ(r.status, status) << r.err;
    EXPECT_EQ(r.err.rfind("tinlod: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(subject), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir)) << "a partial tile set was left";
}

} // namespace

TEST(Tiles, LevelErrorIsCesiums) {
    // CesiumJS: maximumRadius * 2 pi * 0.25 / (65 * 2 tiles at level 0), halved per level.
    EXPECT_NEAR(level_error(0), 77067.34, 0.01);
    EXPECT_NEAR(level_error(12), 18.815, 0.001);
    const GeoRect r = tile_rect({12, 4119, 3007});
    EXPECT_DOUBLE_EQ(r.east - r.west, 180.0 / 4096);
    EXPECT_DOUBLE_EQ(tile_rect({12, 4120, 3007}).west, r.east);
}

TEST(Tiles, DefaultMaxZoomIsTheFirstLevelAsFineAsTheDem) {
    // SRTM3: 1200 spacings a degree; the level whose 65-post heightmap tile (64 spacings) is no
    // coarser than that.
    int z = 0;
    while (180.0 / std::ldexp(1.0, z) / 64.0 > 1.0 / 1200.0)
        ++z;
    EXPECT_EQ(default_max_zoom(load_coverage({asset("N42E001.hgt")}, {})), z);
}

// The bundled SRTM tile's whole pyramid, down to its resolution, read back by the npm decoder.
TEST(Tiles, SrtmPyramidDecodesWithNoCrackAndEveryDemSampleWithinTheLevelsError) {
    if (!decoder_installed())
        FAIL() << "tests/tiles has no node_modules: run scripts/setup.sh (npm ci there)";
    const std::string dir = temp_dir() + "/n42e001";
    const auto r = run_cli("tiles '" + asset("N42E001.hgt") + "' -o '" + dir +
                           "' --normals --stats '" + dir + ".json'");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(file_bytes(dir + ".json"));
    ASSERT_EQ(stats["levels"].size(), 13u);
    for (const auto &level : stats["levels"])
        EXPECT_GT(level["tiles"].get<int>(), 0) << level.dump();
    const auto [rc, report] = check_tiles(dir, quoted(asset("N42E001.hgt")));
    EXPECT_EQ(rc, 0) << report.dump();
    ASSERT_TRUE(report.contains("failures")) << "the checker printed no report";
    EXPECT_TRUE(report["failures"].empty()) << report["failures"].dump(1);
    EXPECT_EQ(report["tiles"], stats["output"]["tiles"]);
    EXPECT_GT(report["shared_edges"].get<int>(), 1000);
    // Every DEM sample is inside a tile of every level: 13 levels of 1201 x 1201 samples, less
    // SRTM's voids (no sample there), and the samples on tile edges counted in each tile.
    EXPECT_GT(report["samples"].get<double>(), 13.0 * (1201.0 * 1201.0 - 7652.0));
    EXPECT_LE(report["worst_ratio"].get<double>(), 1.0);
    EXPECT_GT(report["worst_ratio"].get<double>(), 0.5) << "the bound is not being used";
    // As CesiumJS draws the tiles (triangles flat between Earth-centred vertices): the build
    // reports the same measure.
    EXPECT_LE(report["worst_drawn_ratio"].get<double>(), 1.0);
    EXPECT_NEAR(report["worst_drawn_ratio"].get<double>(),
                stats["error"]["worst_ratio"].get<double>(), 1e-6);
}

TEST(Tiles, TileBuiltAloneIsByteIdenticalToTheSameTileOfTheWholeRun) {
    const std::string dir = temp_dir() + "/set";
    // Two threads: tiles finish in any order in the run.
    const auto r = run_cli("--threads 2 tiles '" + asset("N42E001.hgt") + "' -o '" + dir +
                           "' --normals --min-zoom 5 --max-zoom 10");
    ASSERT_EQ(r.status, 0) << r.err;
    const GeoLattice lattice = load_coverage({asset("N42E001.hgt")}, {});
    TileOptions options;
    options.normals = true;
    int compared = 0;
    for (const auto &f : fs::recursive_directory_iterator(dir)) {
        if (f.path().extension() != ".terrain")
            continue;
        const int y = std::stoi(f.path().stem().string());
        const int x = std::stoi(f.path().parent_path().filename().string());
        const int z = std::stoi(f.path().parent_path().parent_path().filename().string());
        const TileMesh m = build_tile(lattice, {z, x, y}, options);
        const std::vector<std::uint8_t> bytes = gzip_bytes(encode_quantized_mesh(m));
        EXPECT_EQ(std::string(bytes.begin(), bytes.end()), file_bytes(f.path().string()))
            << f.path();
        ++compared;
    }
    EXPECT_GT(compared, 60);
}

TEST(Tiles, AdjacentSrtmTilesFormOneCoverageWithNoSeam) {
    if (!decoder_installed())
        FAIL() << "tests/tiles has no node_modules: run scripts/setup.sh (npm ci there)";
    const std::string dir = temp_dir();
    // A second tile east of the first (the same heights, a degree east): they share the column at
    // 2 degrees east, where the first one given wins.
    fs::copy_file(asset("N42E001.hgt"), dir + "/N42E002.hgt");
    const auto r = run_cli("tiles '" + asset("N42E001.hgt") + "' '" + dir + "/N42E002.hgt' -o '" +
                           dir + "/set' --min-zoom 9 --max-zoom 9 --stats '" + dir + "/s.json'");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(file_bytes(dir + "/s.json"));
    EXPECT_EQ(stats["input"]["nodes"], 2401 * 1201);
    EXPECT_FALSE(stats["input"]["resampled"].get<bool>());
    const auto [rc, report] = check_tiles(dir + "/set", quoted(asset("N42E001.hgt")) + " " +
                                                            quoted(dir + "/N42E002.hgt"));
    EXPECT_EQ(rc, 0) << report.dump();
    EXPECT_TRUE(report["failures"].empty()) << report["failures"].dump(1);
    EXPECT_LE(report["worst_ratio"].get<double>(), 1.0);
}

TEST(Tiles, DemInAnotherCrsIsResampledAndDecodes) {
    if (!decoder_installed())
        FAIL() << "tests/tiles has no node_modules: run scripts/setup.sh (npm ci there)";
    const std::string dir = temp_dir();
    // NAD83 (EPSG:4269), not WGS84: warped with PROJ onto a lattice in WGS84 degrees.
    const auto r = run_cli("tiles '" + asset("dem_squared.tif") + "' -o '" + dir +
                           "/set' --stats '" + dir + "/s.json'");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(file_bytes(dir + "/s.json"));
    EXPECT_TRUE(stats["input"]["resampled"].get<bool>());
    EXPECT_LE(stats["error"]["worst_ratio"].get<double>(), 1.0);
    const auto [rc, report] = check_tiles(dir + "/set", "--no-error");
    EXPECT_EQ(rc, 0) << report.dump();
    EXPECT_TRUE(report["failures"].empty()) << report["failures"].dump(1);
    EXPECT_GT(report["shared_edges"].get<int>(), 0);
}

TEST(Tiles, PartlyCoveredTilesHoldTheFillHeightOutside) {
    const std::string dir = temp_dir();
    for (const double fill : {0.0, 5000.0}) {
        const std::string set = dir + "/fill" + std::to_string(int(fill));
        const auto r = run_cli("tiles '" + asset("dem_srtm30.tif") + "' -o '" + set +
                               "' --max-zoom 3 --fill-height " + std::to_string(fill));
        ASSERT_EQ(r.status, 0) << r.err;
        // The level-0 tile is half the globe: nearly all of it outside the DEM (0 .. 3664 m).
        const auto [lo, hi] = header_heights(set + "/0/1/0.terrain");
        EXPECT_LE(lo, fill);
        EXPECT_GE(hi, fill);
        // Level 0 is written whole (CesiumJS needs both roots), the tile over no DEM at the fill
        // height; below it, only tiles over the DEM.
        const auto [bare_lo, bare_hi] = header_heights(set + "/0/0/0.terrain");
        EXPECT_LE(bare_lo, fill);
        EXPECT_GE(bare_hi, fill);
        EXPECT_FALSE(fs::exists(set + "/1/0/0.terrain")) << "a tile outside the DEM was written";
    }
}

TEST(Tiles, UndergeoreferencedDemIsRefusedAndNoTileSetIsLeft) {
    const std::string dir = temp_dir() + "/set";
    expect_refused(run_cli("tiles '" + asset("crater_u16.png") + "' -o '" + dir + "'"), 1,
                   "crater_u16.png", dir);
    expect_refused(run_cli("tiles '" + dir + ".missing.hgt' -o '" + dir + "'"), 1, "missing", dir);
}

TEST(Tiles, LevelsBeyondTheDemOrOutOfOrderAreUsageErrors) {
    const std::string dir = temp_dir() + "/set";
    expect_refused(
        run_cli("tiles '" + asset("dem_srtm30.tif") + "' -o '" + dir + "' --max-zoom 14"), 2,
        "--max-zoom", dir);
    expect_refused(run_cli("tiles '" + asset("dem_srtm30.tif") + "' -o '" + dir +
                           "' --min-zoom 5 --max-zoom 3"),
                   2, "--min-zoom", dir);
}

TEST(Tiles, FailedWriteLeavesNoPartialTileSet) {
    const std::string dir = temp_dir() + "/set";
    // Files are limited to 100 bytes: the first tile larger than that fails to write.
    const auto r = run_cli("tiles '" + asset("dem_srtm30.tif") + "' -o '" + dir + "'", 100);
    expect_refused(r, 1, dir, dir);
}

TEST(Tiles, InterruptedRunLeavesNoTileSet) {
    const std::string dir = temp_dir() + "/set";
    int interrupted = 0;
    for (int attempt = 0; attempt < 5 && interrupted == 0; ++attempt) {
        const pid_t pid = tinlod::test::start_cli({"tiles", asset("N42E001.hgt"), "-o", dir});
        ASSERT_GT(pid, 0);
        // Once the tiles are being staged in the folder it created, Ctrl-C.
        bool staging = false;
        int status = 0;
        for (int i = 0; i < 20000 && !staging; ++i) {
            std::error_code ec;
            for (const auto &e : fs::directory_iterator(dir, ec))
                staging |= e.path().filename().string().rfind(".staged", 0) == 0;
            if (!staging && waitpid(pid, &status, WNOHANG) == pid)
                break;
            usleep(500);
        }
        if (!staging) { // it finished first (or never staged): start again
            fs::remove_all(dir);
            continue;
        }
        kill(pid, SIGINT);
        waitpid(pid, &status, 0);
        if (WIFEXITED(status) && WEXITSTATUS(status) == 0) { // it finished first
            fs::remove_all(dir);
            continue;
        }
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << status;
        EXPECT_FALSE(fs::exists(dir)) << "the interrupted run left its tile set";
        ++interrupted;
    }
    EXPECT_EQ(interrupted, 1) << "no run could be interrupted while it staged tiles";
}

TEST(Tiles, ProjectedDemIsWarpedWithProj) {
    if (!decoder_installed())
        FAIL() << "tests/tiles has no node_modules: run scripts/setup.sh (npm ci there)";
    const std::string dir = temp_dir();
    // 2 x 2 samples 30 m apart in UTM zone 31N (EPSG:32631), south-west of (500000, 4e6).
    std::ofstream(dir + "/utm.tif", std::ios::binary)
        << test::geotiff_bytes({{33550, {30.0, 30.0, 0.0}}, {33922, {0, 0, 0, 500000.0, 4e6, 0}}},
                               {1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32631});
    const auto r =
        run_cli("tiles '" + dir + "/utm.tif' -o '" + dir + "/set' --stats '" + dir + "/s.json'");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(file_bytes(dir + "/s.json"));
    EXPECT_TRUE(stats["input"]["resampled"].get<bool>());
    EXPECT_GT(stats["input"]["covered"].get<int>(), 0);
    // 30 m is about 1/3700 of a degree of latitude.
    EXPECT_NEAR(stats["input"]["spacing_deg"][1].get<double>(), 30.0 / 111000.0, 2e-5);
    EXPECT_LE(stats["error"]["worst_ratio"].get<double>(), 1.0);
    const auto [rc, report] = check_tiles(dir + "/set", "--no-error");
    EXPECT_EQ(rc, 0) << report.dump();
    EXPECT_TRUE(report["failures"].empty()) << report["failures"].dump(1);
}

TEST(Tiles, OutputThatIsAFileIsRefusedAndKept) {
    const std::string file = temp_dir() + "/taken";
    std::ofstream(file) << "not a folder";
    const auto r = run_cli("tiles '" + asset("dem_srtm30.tif") + "' -o '" + file + "'");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_EQ(file_bytes(file), "not a folder");
}
