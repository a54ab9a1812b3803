// Rasters read as the terrain they hold or refused with a reason: pixels that are not heights
// (alpha, a tRNS key, colour), georeferencing the loader cannot honour, declared sizes beyond the
// machine's memory, and large voids filled smoothly.
#include "assets.hpp"

#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace tinlod;
using tinlod::test::asset;
using tinlod::test::png_bytes;

namespace {

std::string write(const std::string &dir, const std::string &name, const std::string &bytes) {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// The reason load_heightfield gives for refusing `path` (fails the test if it loads).
std::string refusal(const std::string &path, const LoadOptions &options = {}) {
    try {
        load_heightfield(path, options);
    } catch (const Error &e) {
        EXPECT_EQ(e.subject(), path);
        return e.reason();
    }
    ADD_FAILURE() << path << " loaded";
    return "";
}

bool contains(const std::string &text, const std::string &part) {
    return text.find(part) != std::string::npos;
}

} // namespace

// Alpha says which samples exist, not how high they are: a half-transparent 1000 m sample is
// 1000 m (it read as 500 m, premultiplied), a transparent one is a void, filled from its
// neighbours and counted (it read as 0 m).
TEST(RasterInput, GreyAlphaPngAlphaMarksVoidsAndNeverScalesHeights) {
    const std::string dir = test::temp_dir();
    // 3 x 3 grey+alpha, 16 bits: heights 1000..1800, the centre transparent, one corner at 50 %.
    std::vector<unsigned> samples;
    for (unsigned i = 0; i < 9; ++i)
        samples.insert(samples.end(), {1000 + 100 * i, i == 4 ? 0u : i == 0 ? 32768u : 65535u});
    const Heightfield hf = load_heightfield(write(dir, "ga.png", png_bytes(3, 3, 4, 16, samples)));
    EXPECT_EQ(hf.voids, 1);
    EXPECT_EQ(hf.filled, 1);
    // File row 0 (north) is Heightfield row 2.
    EXPECT_FLOAT_EQ(hf.at(0, 2), 1000.0f);
    EXPECT_FLOAT_EQ(hf.at(2, 0), 1800.0f);
    ASSERT_EQ(hf.void_mask.size(), 9u);
    EXPECT_EQ(hf.void_mask[4], 1);
    // The void lies within its neighbours' heights, far from 0 m.
    EXPECT_GE(hf.at(1, 1), 1000.0f);
    EXPECT_LE(hf.at(1, 1), 1800.0f);
}

// A tRNS key in a grey PNG names missing samples: voids, and an image of nothing but the key is
// the all-void error (it read as a flat 0 m DEM).
TEST(RasterInput, GreyPngTrnsKeyIsAVoid) {
    const std::string dir = test::temp_dir();
    const std::string key{0, 7}; // 16-bit grey key: 7
    const std::string some = write(
        dir, "key.png", png_bytes(3, 2, 0, 16, {1000, 7, 1200, 1300, 1400, 1500}, {{"tRNS", key}}));
    const Heightfield hf = load_heightfield(some);
    EXPECT_EQ(hf.voids, 1);
    EXPECT_GE(hf.min_z(), 1000.0f);
    const std::string all =
        write(dir, "allkey.png", png_bytes(2, 2, 0, 16, {7, 7, 7, 7}, {{"tRNS", key}}));
    EXPECT_TRUE(contains(refusal(all), "every sample is a void")) << refusal(all);
}

// Colour is not height: RGB, RGBA and palette images are refused, and an 8-bit RGB one is
// pointed to --terrain-rgb (Mapbox's own Terrain-RGB tile read as a flat DEM of 1 m).
TEST(RasterInput, ColourImagesAreRefusedAndTerrainRgbIsNamed) {
    const std::string dir = test::temp_dir();
    const std::string rgb = write(dir, "rgb.png", png_bytes(2, 2, 2, 8, std::vector(12, 9u)));
    EXPECT_TRUE(contains(refusal(rgb), "use --terrain-rgb")) << refusal(rgb);
    const std::string fuji = asset("fuji.png"); // RGBA8
    EXPECT_TRUE(contains(refusal(fuji), "use --terrain-rgb")) << refusal(fuji);
    const std::string rgba16 =
        write(dir, "rgba16.png", png_bytes(2, 2, 6, 16, std::vector(16, 65535u)));
    const std::string why = refusal(rgba16);
    EXPECT_TRUE(contains(why, "not a DEM")) << why;
    EXPECT_FALSE(contains(why, "terrain-rgb")) << why;
    const std::string palette = write(
        dir, "palette.png",
        png_bytes(2, 2, 3, 8, {0, 1, 1, 0}, {{"PLTE", std::string("\0\0\0\xff\xff\xff", 6)}}));
    EXPECT_TRUE(contains(refusal(palette), "palette")) << refusal(palette);
    // With the flag, the same tile is terrain.
    LoadOptions options;
    options.terrain_rgb = true;
    EXPECT_GT(load_heightfield(fuji, options).max_z(), 3000.0f);
    // The command line says it in one line, exit status 1.
    const test::RunResult r = test::run_cli("info '" + fuji + "'");
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.err, "fuji.png: ") && contains(r.err, "use --terrain-rgb")) << r.err;
}

namespace {

// A 2 x 2 int16 GeoTIFF of test::geotiff_bytes placed in UTM zone 31N (EPSG:32631, or `epsg`)
// by a pixel scale and a tie point of pixel (0, 0) at (500000, 4e6).
std::string utm_tiff(const std::string &dir, const std::string &name, double sx, double sy,
                     unsigned epsg = 32631, const std::string &nodata = "") {
    return write(
        dir, name,
        test::geotiff_bytes({{33550, {sx, sy, 0.0}}, {33922, {0.0, 0.0, 0.0, 500000.0, 4e6, 0.0}}},
                            {1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, epsg}, nodata));
}

} // namespace

// A negative pixel scale runs the file's columns west or its rows north: each sample must still
// stand at the coordinates the georeferencing gives it (the absolute value mirrored the terrain).
TEST(RasterInput, NegativePixelScaleKeepsEverySampleAtItsCoordinates) {
    const std::string dir = test::temp_dir();
    const float heights[2][2] = {{100, 200}, {300, 400}}; // file rows, as geotiff_bytes writes
    for (const auto &[sx, sy] :
         {std::pair{30.0, 30.0}, {-30.0, 30.0}, {30.0, -30.0}, {-30.0, -30.0}}) {
        SCOPED_TRACE(std::to_string(sx) + ", " + std::to_string(sy));
        const Heightfield hf = load_heightfield(utm_tiff(dir, "s.tif", sx, sy));
        EXPECT_DOUBLE_EQ(hf.dx, 30.0);
        EXPECT_DOUBLE_EQ(hf.dy, 30.0);
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                // The centre of file sample (i, j) in the CRS, then in the Heightfield's grid.
                const double x = 500000.0 + (i + 0.5) * sx, y = 4e6 - (j + 0.5) * sy;
                const double col = (x - hf.origin_x) / hf.dx, row = (y - hf.origin_y) / hf.dy;
                ASSERT_NEAR(col, std::round(col), 1e-9);
                ASSERT_NEAR(row, std::round(row), 1e-9);
                EXPECT_EQ(hf.at(int(std::lround(col)), int(std::lround(row))), heights[j][i]);
            }
    }
}

// Georeferencing the loader cannot honour is refused, never guessed: an EPSG code PROJ does not
// know (it was taken as metres), a GDAL_NODATA that is no number (it was ignored).
TEST(RasterInput, UnknownEpsgAndNonNumericNodataAreRefused) {
    const std::string dir = test::temp_dir();
    const std::string unknown = utm_tiff(dir, "epsg.tif", 30, 30, 65000);
    EXPECT_TRUE(contains(refusal(unknown), "EPSG:65000")) << refusal(unknown);
    const std::string feet = utm_tiff(dir, "feet.tif", 30, 30, 2227); // California zone 3, US ft
    EXPECT_TRUE(contains(refusal(feet), "not metres")) << refusal(feet);
    const std::string abc = utm_tiff(dir, "abc.tif", 30, 30, 32631, "abc");
    EXPECT_TRUE(contains(refusal(abc), "GDAL_NODATA is 'abc'")) << refusal(abc);
    const std::string trailing = utm_tiff(dir, "trailing.tif", 30, 30, 32631, "-9999x");
    EXPECT_TRUE(contains(refusal(trailing), "not a number")) << refusal(trailing);
    // A number, even with spaces around it, is a nodata value: here no sample is one.
    EXPECT_EQ(load_heightfield(utm_tiff(dir, "ok.tif", 30, 30, 32631, " -9999 ")).voids, 0);
    EXPECT_EQ(load_heightfield(utm_tiff(dir, "void.tif", 30, 30, 32631, "300")).voids, 1);
}

// --cell is the spacing of a raster without georeferencing: an .hgt file that is not named as an
// SRTM tile needs it (it was read as a 1 m grid), and a georeferenced raster refuses it (it was
// ignored).
TEST(RasterInput, CellIsNeededByAnUnnamedHgtAndRefusedByAGeoreferencedRaster) {
    const std::string dir = test::temp_dir();
    std::ifstream in(asset("N42E001.hgt"), std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), {}};
    const std::string foo = write(dir, "foo.hgt", bytes);
    EXPECT_TRUE(contains(refusal(foo), "--cell")) << refusal(foo);
    LoadOptions cell;
    cell.cell = 90.0;
    const Heightfield hf = load_heightfield(foo, cell);
    EXPECT_DOUBLE_EQ(hf.dx, 90.0);
    EXPECT_EQ(hf.width, 1201);
    const std::string tif = asset("dem_squared.tif");
    EXPECT_TRUE(contains(refusal(tif, cell), "--cell")) << refusal(tif, cell);
    const test::RunResult r = test::run_cli("info --json --cell 90 '" + foo + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto info = nlohmann::json::parse(r.out);
    EXPECT_EQ(info["cell_size"], nlohmann::json::array({90.0, 90.0})) << r.out;
}

namespace {

// Runs the CLI with `args` (not through a shell); returns its exit status, its stderr and its
// peak resident memory in MiB.
struct Measured {
    int status = -1;
    std::string err;
    double peak_mib = 0;
};
Measured run_measured(const std::vector<std::string> &args) {
    const std::string err_file = test::temp_dir() + "/err";
    const pid_t pid = test::start_cli(args, err_file);
    int raw = 0;
    rusage usage{};
    wait4(pid, &raw, 0, &usage);
    Measured m;
    m.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    std::ifstream in(err_file);
    m.err.assign(std::istreambuf_iterator<char>(in), {});
    m.peak_mib = double(usage.ru_maxrss) / 1024.0;
    return m;
}

// The MiB figure of a memory refusal ("needs about N MiB"), or -1.
double needed_mib(const std::string &err) {
    const auto at = err.find("needs about ");
    return at == std::string::npos ? -1 : std::stod(err.substr(at + 12));
}

} // namespace

// A small file may declare a huge raster: the memory a command needs is estimated from the header
// and refused, naming the file and the figure, before anything is allocated (a 760 KB PNG of
// 20000 x 20000 samples took 3.9 GB for `info`).
TEST(RasterInput, HugeDeclaredRasterIsRefusedBeforeAllocating) {
    const std::string dir = test::temp_dir();
    const std::string png = write(dir, "huge.png", png_bytes(20000, 20000, 0, 8, {}));
    const auto start = std::chrono::steady_clock::now();
    const Measured m = run_measured({"info", png, "--max-memory-mb", "1000"});
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(m.status, 1);
    EXPECT_TRUE(contains(m.err, "huge.png: ") && contains(m.err, "20000x20000")) << m.err;
    // At least the samples as read and as floats: 5 bytes each.
    EXPECT_GE(needed_mib(m.err), 20000.0 * 20000.0 * 5 / (1 << 20)) << m.err;
    EXPECT_LT(m.peak_mib, 200.0);
    EXPECT_LT(seconds, 10.0);
    // A command that does more with each sample needs more: retrieve's estimate exceeds info's.
    const Measured info = run_measured({"info", png, "--max-memory-mb", "100"});
    const Measured retrieve =
        run_measured({"retrieve", png, "--full", "-o", dir + "/out.ply", "--max-memory-mb", "100"});
    EXPECT_GT(needed_mib(retrieve.err), needed_mib(info.err)) << info.err << retrieve.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/out.ply"));
}

// Without --max-memory-mb the limit is this machine's memory: a raster of 2^31 samples is more
// than `retrieve` can hold on any machine this test runs on.
TEST(RasterInput, DefaultLimitIsThisMachinesMemory) {
    const std::string dir = test::temp_dir();
    const std::string png = write(dir, "big.png", png_bytes(46340, 46340, 0, 16, {}));
    const Measured m = run_measured({"retrieve", png, "--full", "-o", dir + "/out.ply"});
    const double have_mib =
        double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)) / (1 << 20);
    if (needed_mib(m.err) < 0 && have_mib > 46340.0 * 46340.0 * 20 / (1 << 20))
        GTEST_SKIP() << "this machine holds " << have_mib << " MiB";
    EXPECT_EQ(m.status, 1);
    EXPECT_TRUE(contains(m.err, "big.png: ") && contains(m.err, "this machine's")) << m.err;
    EXPECT_GT(needed_mib(m.err), 0.9 * have_mib) << m.err;
    EXPECT_LT(m.peak_mib, 200.0);
}

// A TIFF declaring tiles of 2^30 x 2^30 samples failed with "out of memory" and no file name.
TEST(RasterInput, HugeTiffTilesAreRefusedNamingTheFile) {
    const std::string dir = test::temp_dir();
    const std::string tif =
        write(dir, "tiles.tif", test::tiled_tiff_bytes(2, 2, 1u << 30, 1u << 30));
    const std::string why = refusal(tif);
    EXPECT_TRUE(contains(why, "needs about")) << why;
    const Measured m = run_measured({"info", tif});
    EXPECT_EQ(m.status, 1);
    EXPECT_TRUE(contains(m.err, "tiles.tif: ")) << m.err;
}

namespace {

// N42E001 with a square hole of side `side` punched (voids) at file row and column `at`, written
// under its own name in `dir`.
std::string punched_n42e001(const std::string &dir, int at, int side) {
    std::ifstream in(asset("N42E001.hgt"), std::ios::binary);
    std::string bytes{std::istreambuf_iterator<char>(in), {}};
    for (int r = at; r < at + side; ++r)
        for (int c = at; c < at + side; ++c) {
            bytes[2 * (std::size_t(r) * 1201 + c)] = char(0x80); // -32768, big-endian
            bytes[2 * (std::size_t(r) * 1201 + c) + 1] = 0;
        }
    return write(dir, "N42E001.hgt", bytes);
}

} // namespace

// A large void is filled by the harmonic interpolation of its boundary: each filled value is the
// mean of its 4 neighbours, and the fill stays within the boundary's range, so a shaded render
// shows no terraces (the ring-by-ring average was flat on each ring, and fails the mean test).
TEST(RasterInput, LargeVoidIsFilledSmoothlyWithinItsBoundary) {
    const std::string dir = test::temp_dir();
    const int at = 520, side = 150; // 22,500 samples in the mountains of Andorra
    const Heightfield hf = load_heightfield(punched_n42e001(dir, at, side));
    EXPECT_GE(hf.voids, side * side);
    EXPECT_EQ(hf.filled, hf.voids);
    ASSERT_EQ(hf.void_mask.size(), std::size_t(hf.size()));
    const auto is_void = [&](int c, int r) { return hf.void_mask[std::size_t(r) * hf.width + c]; };
    // The hole's region (with any real voids it touches) and the valid samples around it.
    std::vector<std::pair<int, int>> region{{at + side / 2, hf.height - 1 - (at + side / 2)}};
    std::vector<std::uint8_t> seen(std::size_t(hf.size()), 0);
    seen[std::size_t(region[0].second) * hf.width + region[0].first] = 1;
    float lo = 1e30f, hi = -1e30f;
    double worst = 0;
    for (std::size_t k = 0; k < region.size(); ++k) {
        const auto [c, r] = region[k];
        ASSERT_TRUE(is_void(c, r));
        double sum = 0;
        int count = 0;
        for (const auto &[dc, dr] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            const int cc = c + dc, rr = r + dr;
            if (cc < 0 || rr < 0 || cc >= hf.width || rr >= hf.height)
                continue;
            sum += hf.at(cc, rr);
            ++count;
            if (!is_void(cc, rr)) {
                lo = std::min(lo, hf.at(cc, rr));
                hi = std::max(hi, hf.at(cc, rr));
            } else if (!seen[std::size_t(rr) * hf.width + cc]) {
                seen[std::size_t(rr) * hf.width + cc] = 1;
                region.emplace_back(cc, rr);
            }
        }
        worst = std::max(worst, std::abs(hf.at(c, r) - sum / count));
    }
    EXPECT_GE(region.size(), std::size_t(side) * side);
    EXPECT_LT(worst, 0.01) << "a filled value differs from its neighbours' mean";
    ASSERT_LT(lo, hi);
    for (const auto &[c, r] : region) {
        EXPECT_GE(hf.at(c, r), lo - 1e-3f);
        EXPECT_LE(hf.at(c, r), hi + 1e-3f);
    }
}
