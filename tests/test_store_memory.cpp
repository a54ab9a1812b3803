// `tinlod build` within --memory-mb (issue #49, item 1): past the memory given, the DEM is read by
// windows and the store written tile by tile, the same bytes as the whole-raster build; `simplify
// STORE` with a camera and --tol holds the retrieved TIN and the tiles of --cache-mb, not the
// raster, and keeps the bound at every sample.
#include "assets.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/view.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiffio.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

using namespace tinlod::test;

namespace {

// Writes a w x h float32 TIFF in tiles of `tile` samples, a rough terrain of ridges and noise.
void write_tiled_float_tiff(const std::string &path, std::uint32_t w, std::uint32_t h,
                            std::uint32_t tile) {
    TIFF *tif = TIFFOpen(path.c_str(), "w");
    ASSERT_NE(tif, nullptr);
    TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, w);
    TIFFSetField(tif, TIFFTAG_IMAGELENGTH, h);
    TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, 32);
    TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_IEEEFP);
    TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(tif, TIFFTAG_TILEWIDTH, tile);
    TIFFSetField(tif, TIFFTAG_TILELENGTH, tile);
    std::vector<float> buffer(std::size_t{tile} * tile);
    std::uint32_t noise = 12345;
    for (std::uint32_t y = 0; y < h; y += tile)
        for (std::uint32_t x = 0; x < w; x += tile) {
            for (std::uint32_t r = 0; r < tile; ++r)
                for (std::uint32_t c = 0; c < tile; ++c) {
                    noise = noise * 1664525u + 1013904223u;
                    const double u = x + c, v = y + r;
                    buffer[std::size_t{r} * tile + c] =
                        float(500.0 + 300.0 * std::sin(u * 0.013) * std::cos(v * 0.021) +
                              40.0 * std::abs(std::sin((u + 2.0 * v) * 0.07)) +
                              double(noise >> 24) * 0.05);
                }
            TIFFWriteTile(tif, buffer.data(), x, y, 0, 0);
        }
    TIFFClose(tif);
}

struct Built {
    std::string bytes;
    nlohmann::json stats;
};

// `tinlod build DEM` with `options`, the store's bytes and the stats.
Built build(const std::string &dem, const std::string &options, const std::string &name) {
    const std::string store = temp_dir() + "/" + name + ".tlq",
                      stats = temp_dir() + "/" + name + ".json";
    const RunResult r =
        run_cli("build '" + dem + "' -o '" + store + "' --stats '" + stats + "' " + options);
    EXPECT_EQ(r.status, 0) << r.err;
    if (r.status != 0)
        return {};
    return {file_bytes(store), nlohmann::json::parse(file_bytes(stats))};
}

// The build by windows (--memory-mb 1: bands of a tile row or a few) against the whole one.
void expect_same_store(const std::string &dem, const std::string &name) {
    const Built whole = build(dem, "--memory-mb 100000", name + "-whole");
    const Built windows = build(dem, "--memory-mb 1", name + "-windows");
    ASSERT_FALSE(whole.bytes.empty());
    EXPECT_EQ(whole.stats["input"]["read"], "whole");
    EXPECT_EQ(windows.stats["input"]["read"], "by windows");
    EXPECT_TRUE(windows.bytes == whole.bytes) << name << ": the stores differ";
}

} // namespace

// The bundled SRTM tile, voids and all.
TEST(StoreMemory, BuildByWindowsEqualsWholeBuildOnSrtm) {
    expect_same_store(asset("N42E001.hgt"), "srtm");
}

// A tiled float GeoTIFF-like raster of odd size: bands of tile rows over levels whose nodes span
// many bands.
TEST(StoreMemory, BuildByWindowsEqualsWholeBuildOnTiledTiff) {
    const std::string dem = temp_dir() + "/tiled.tif";
    write_tiled_float_tiff(dem, 1111, 777, 128);
    expect_same_store(dem, "tiled");
}

// Thin and tiny grids, in bands of one or several tile rows: one-cell-wide nodes above the tiles
// spanning many bands, a single tile, no node bounds at all.
TEST(StoreMemory, StoreByRowsEqualsStoreOfTheTreeOnOddShapes) {
    const std::pair<int, int> shapes[] = {{2, 2},    {3, 200},   {300, 7},  {2, 300},
                                          {1000, 3}, {257, 129}, {130, 517}};
    for (const auto &[w, h] : shapes) {
        tinlod::Heightfield hf;
        hf.width = w;
        hf.height = h;
        hf.dx = 30.0;
        hf.dy = 20.0;
        hf.crs = "local";
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c)
                hf.z.push_back(float(500.0 + 300.0 * std::sin(c * 0.05) * std::cos(r * 0.07) +
                                     (c * 7919 + r * 104729) % 97));
        const std::string name = temp_dir() + "/odd" + std::to_string(w) + "x" + std::to_string(h);
        tinlod::write_store(tinlod::QuadTree(hf), name + "-tree.tlq");
        const tinlod::GridFrame frame{w, h, hf.dx, hf.dy, 0.0, 0.0, hf.crs};
        // Bands of a tile row, and of about 200 rows (tile rows of 33 to 65 rows, by threes or
        // more, across the nodes above them).
        for (const int band_rows : {1, 200}) {
            tinlod::write_store_by_rows(
                frame,
                [&hf](int r0, int r1) {
                    return std::vector<float>(hf.z.begin() + std::ptrdiff_t(r0) * hf.width,
                                              hf.z.begin() + std::ptrdiff_t(r1) * hf.width);
                },
                4 * std::int64_t(w) * band_rows, name + "-rows.tlq");
            EXPECT_TRUE(file_bytes(name + "-tree.tlq") == file_bytes(name + "-rows.tlq"))
                << w << "x" << h << ", bands of " << band_rows << " rows: the stores differ";
        }
    }
}

// The bounded build holds a band of rows, not the raster: its peak stays below the whole build's
// by more than the raster's heights (a 2049 x 2049 float raster: 16 MiB of heights, about 50 MiB
// of heights and bounds for the whole build).
TEST(StoreMemory, BuildByWindowsHoldsLessThanTheRaster) {
    const std::string dem = temp_dir() + "/big.tif";
    write_tiled_float_tiff(dem, 2049, 2049, 256);
    const Built whole = build(dem, "--memory-mb 100000", "big-whole");
    const Built windows = build(dem, "--memory-mb 52", "big-windows");
    ASSERT_FALSE(whole.bytes.empty());
    EXPECT_TRUE(windows.bytes == whole.bytes);
    const double heights_mb = 2049.0 * 2049.0 * 4.0 / (1024.0 * 1024.0);
    const double whole_mb = whole.stats["peak_rss_mb"], windows_mb = windows.stats["peak_rss_mb"];
    EXPECT_LT(windows_mb + heights_mb, whole_mb)
        << "by windows " << windows_mb << " MB, whole " << whole_mb << " MB";
}

// simplify STORE with a camera and a budget retrieves from the store's bounds, its tiles through a
// cache of --cache-mb (1 MiB: tiles evicted between the retrievals of the budget's search), and
// erases on the heights read whole: the TIN the DEM gives, node for node.
TEST(StoreMemory, SimplifyStoreWithABudgetGivesTheDemsTin) {
    const std::string dem = asset("N42E001.hgt"), store = temp_dir() + "/simplify.tlq";
    ASSERT_EQ(run_cli("build '" + dem + "' -o '" + store + "'").status, 0);
    const std::string view = " --eye 41000,50000,20000 --at 41000,55000,980 ";
    for (const std::string mode : {"--max-nodes 3000"}) {
        const std::string from_dem = temp_dir() + "/from-dem.ply",
                          from_store = temp_dir() + "/from-store.ply";
        const RunResult a = run_cli("simplify '" + dem + "'" + view + mode + " -o " + from_dem);
        const RunResult b =
            run_cli("simplify '" + store + "'" + view + mode + " --cache-mb 1 -o " + from_store);
        ASSERT_EQ(a.status, 0) << a.err;
        ASSERT_EQ(b.status, 0) << b.err;
        EXPECT_TRUE(file_bytes(from_dem) == file_bytes(from_store)) << mode << ": the TINs differ";
    }
}

namespace {

// Smooth hills at sample (c, r): write_tiled_float_tiff's terrain without its ridges and noise,
// so that a view retrieves a small share of the samples.
float hills(int c, int r) {
    return float(500.0 + 300.0 * std::sin(c * 0.013) * std::cos(r * 0.021));
}

} // namespace

// simplify STORE with a camera and --tol erases without the heights: every sample of the DEM the
// store came from is within the bound (measured here on the DEM, by measure_error, not by the
// erase's walk), from a near view and a low oblique one that retrieves the whole raster, through a
// cache of 0.25 MiB (about 12 of its 100 tiles). The DEM: the middle 601² of N42E001.
TEST(StoreMemory, SimplifyStoreWithTolKeepsTheBoundAtEverySample) {
    const std::string store = temp_dir() + "/bound.tlq";
    const tinlod::Heightfield hf =
        crop(tinlod::load_heightfield(asset("N42E001.hgt")), 300, 300, 601, 601);
    tinlod::write_store(tinlod::QuadTree(hf), store);
    const double w = (hf.width - 1) * hf.dx, h = (hf.height - 1) * hf.dy;
    const auto point = [](double x, double y, double z) {
        return std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z);
    };
    const std::pair<std::string, std::string> views[] = {
        {point(w / 2, h / 3, 20000), point(w / 2, h / 2, 980)},
        {point(w / 2, -3000, 1600), point(w / 2, h, 800)}};
    for (const auto &[eye, at] : views) {
        const std::string out = temp_dir() + "/bound.ply", stats = temp_dir() + "/bound.json";
        const RunResult r = run_cli("simplify '" + store + "' --eye " + eye + " --at " + at +
                                    " --tol 1 --cache-mb 0.25 -o " + out + " --stats " + stats);
        ASSERT_EQ(r.status, 0) << r.err;
        const tinlod::Mesh tin = tinlod::read_mesh(out);
        tinlod::ErrorOptions eo;
        tinlod::View view; // the CLI's default fov and viewport
        view.eye = tinlod::parse_vec3(eye, "eye");
        view.at = tinlod::parse_vec3(at, "at");
        eo.model = tinlod::Significance::screen(view);
        const tinlod::TinError e = tinlod::measure_error(hf, tin, eo);
        EXPECT_LE(e.max_screen_px, 1.0 + 1e-9) << eye;
        EXPECT_GT(e.max_screen_px, 0.5) << eye << ": the erase did not use the bound";
        EXPECT_EQ(e.uncovered, 0) << eye;
        EXPECT_EQ(count_folded_faces(tin), 0) << eye;
        // The stats' error is the store's own measure: the same as the DEM's.
        const nlohmann::json j = nlohmann::json::parse(file_bytes(stats));
        EXPECT_NEAR(double(j["error"]["max_screen_px"]), e.max_screen_px, 1e-9) << eye;
        EXPECT_NEAR(double(j["error"]["max_vertical"]), e.max_vertical, 1e-9) << eye;
        EXPECT_LT(tin.n_vertices(), std::size_t(j["retrieve"]["nodes"])) << eye;
    }
}

// The same run holds the retrieved TIN and the tiles of --cache-mb, not the raster: on a 2049²
// store of smooth hills (16 MiB of heights; the erase on the heights read whole peaks over 100
// MiB), from a low oblique view that retrieves across the whole raster, the peak stays under a base
// for the program and its libraries, the cache, and 2 KiB per retrieved node (the TIN's mesh, its
// copy and the retrieval's buffers). The store is written here by rows, and the peak is the CLI's
// own (its stats' VmHWM): getrusage's RUSAGE_CHILDREN would count the test's own pages, which a
// forked child holds until it runs the CLI.
TEST(StoreMemory, SimplifyStoreWithTolHoldsTheRetrievedTinNotTheRaster) {
    const int side = 2049;
    const std::string store = temp_dir() + "/rss.tlq", stats = temp_dir() + "/rss.json";
    tinlod::write_store_by_rows(
        tinlod::GridFrame{side, side, 10.0, 10.0, 0.0, 0.0, "local"},
        [](int r0, int r1) {
            std::vector<float> rows;
            rows.reserve(std::size_t(r1 - r0) * side);
            for (int r = r0; r < r1; ++r)
                for (int c = 0; c < side; ++c)
                    rows.push_back(hills(c, r));
            return rows;
        },
        std::int64_t(4) << 20, store);
    const double cache_mb = 8.0;
    const RunResult r = run_cli(
        "simplify '" + store + "' --eye 10240,-1500,1200 --at 10240,10000,600 --tol 1 --cache-mb " +
        std::to_string(cache_mb) + " -o " + temp_dir() + "/rss.ply --stats " + stats);
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(file_bytes(stats));
    const double retrieved = j["retrieve"]["nodes"], peak_mb = j["peak_rss_mb"];
    const double bound_mb = 30.0 + cache_mb + 2.0 * retrieved / 1024.0;
    EXPECT_LT(peak_mb, bound_mb) << retrieved << " nodes retrieved";
}

// The bounded path checks the eye against the store's surface too, without reading it whole.
TEST(StoreMemory, SimplifyStoreWithTolRefusesAnEyeUnderTheGround) {
    const std::string store = temp_dir() + "/eye.tlq";
    ASSERT_EQ(run_cli("build '" + asset("N42E001.hgt") + "' -o '" + store + "'").status, 0);
    const RunResult r =
        run_cli("simplify '" + store + "' --eye 41000,50000,10 --at 41000,55000,980 --tol 1 -o " +
                temp_dir() + "/eye.ply");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("inside the terrain"), std::string::npos) << r.err;
}

// A tile whose bytes changed is refused on the bounded path too (every tile the erase or the
// measure reads is verified), with no output file.
TEST(StoreMemory, SimplifyStoreWithTolRefusesACorruptTile) {
    const std::string store = temp_dir() + "/corrupt.tlq", out = temp_dir() + "/corrupt.ply";
    ASSERT_EQ(run_cli("build '" + asset("N42E001.hgt") + "' -o '" + store + "'").status, 0);
    std::string bytes = file_bytes(store);
    // Tiles fill most of the file: one of these lands in a tile's samples or bounds.
    for (const double at : {0.5, 0.6, 0.7})
        bytes[std::size_t(at * double(bytes.size()))] ^= 0x5a;
    {
        std::ofstream f(store, std::ios::binary | std::ios::trunc);
        f << bytes;
    }
    const RunResult r = run_cli("simplify '" + store +
                                "' --eye 60000,-3000,1600 --at 60000,40000,800 --tol 1 -o " + out);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("corrupt tile"), std::string::npos) << r.err;
    EXPECT_TRUE(file_bytes(out).empty());
}
