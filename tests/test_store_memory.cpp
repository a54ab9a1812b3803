// `tinlod build` within --memory-mb (issue #49, item 1): past the memory given, the DEM is read by
// windows and the store written tile by tile, the same bytes as the whole-raster build; `simplify
// STORE` retrieves from the store's bounds.
#include "assets.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/store.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiffio.h>

#include <cmath>
#include <cstdint>
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

// simplify STORE with a camera retrieves from the store's bounds, its tiles through a cache of
// --cache-mb (1 MiB: tiles evicted between the retrievals of a budget's search): the TIN the DEM
// gives, node for node, with a bound and with a budget.
TEST(StoreMemory, SimplifyStoreGivesTheDemsTin) {
    const std::string dem = asset("N42E001.hgt"), store = temp_dir() + "/simplify.tlq";
    ASSERT_EQ(run_cli("build '" + dem + "' -o '" + store + "'").status, 0);
    const std::string view = " --eye 41000,50000,20000 --at 41000,55000,980 ";
    for (const std::string mode : {"--tol 1", "--max-nodes 3000"}) {
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
