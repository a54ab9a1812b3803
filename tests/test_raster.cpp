// Foundation: every bundled DEM loads with the size, value range and voids its MANIFEST lists;
// georeferencing gives the ground spacing the latitude implies.
#include "assets.hpp"

#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace tinlod;
using tinlod::test::asset;

namespace {

struct ManifestRow {
    const char *file;
    int width, height;
    float min, max;
    std::int64_t voids;
    bool terrain_rgb;
};

// Values typed from meshes/MANIFEST.md (copied from the data's own manifest).
const ManifestRow k_manifest[] = {
    {"N42E001.hgt", 1201, 1201, 349.f, 3100.f, 7652, false},
    {"dem_squared.tif", 129, 129, 65.358f, 318.441f, 0, false},
    {"dem_srtm30.tif", 300, 300, 0.f, 3664.f, 0, false},
    {"crater_u16.png", 336, 459, 1533.f, 2478.f, 0, false},
    {"fuji.png", 512, 512, 13.7f, 3751.0f, 0, true},
};

} // namespace

TEST(Raster, EveryBundledDemMatchesItsManifest) {
    for (const auto &row : k_manifest) {
        SCOPED_TRACE(row.file);
        LoadOptions options;
        options.terrain_rgb = row.terrain_rgb;
        const Heightfield hf = load_heightfield(asset(row.file), options);
        EXPECT_EQ(hf.width, row.width);
        EXPECT_EQ(hf.height, row.height);
        EXPECT_EQ(hf.voids, row.voids);
        EXPECT_EQ(hf.filled, row.voids);
        EXPECT_NEAR(hf.min_z(), row.min, 1e-3);
        EXPECT_NEAR(hf.max_z(), row.max, 1e-3);
        EXPECT_GT(hf.dx, 0.0);
        EXPECT_GT(hf.dy, 0.0);
    }
}

TEST(Raster, VoidsAreFilledFromNeighboursNeverBecomeSpikes) {
    const Heightfield hf = load_heightfield(asset("N42E001.hgt"));
    ASSERT_EQ(hf.void_mask.size(), std::size_t(hf.size()));
    std::int64_t marked = 0;
    for (int r = 1; r + 1 < hf.height; ++r)
        for (int c = 1; c + 1 < hf.width; ++c) {
            if (!hf.void_mask[std::size_t(r) * hf.width + c])
                continue;
            ++marked;
            // A filled void lies within the range of its 8 neighbours (their average or better).
            float lo = 1e30f, hi = -1e30f;
            for (int dr = -1; dr <= 1; ++dr)
                for (int dc = -1; dc <= 1; ++dc)
                    if (dr || dc) {
                        lo = std::min(lo, hf.at(c + dc, r + dr));
                        hi = std::max(hi, hf.at(c + dc, r + dr));
                    }
            EXPECT_GE(hf.at(c, r), lo - 1e-3f);
            EXPECT_LE(hf.at(c, r), hi + 1e-3f);
        }
    EXPECT_GT(marked, 7000);
}

TEST(Raster, DemSquaredCornersMatchManifest) {
    const Heightfield hf = load_heightfield(asset("dem_squared.tif"));
    // MANIFEST lists the corners in file order: north-west, north-east, south-west, south-east.
    // Row 0 of the Heightfield is the south edge.
    const int n = hf.width - 1;
    EXPECT_NEAR(hf.at(0, n), 215.82324, 1e-4);
    EXPECT_NEAR(hf.at(n, n), 216.04961, 1e-4);
    EXPECT_NEAR(hf.at(0, 0), 142.2274, 1e-4);
    EXPECT_NEAR(hf.at(n, 0), 209.14784, 1e-4);
}

TEST(Raster, GeographicSpacingFollowsLatitude) {
    // One arc-second of latitude is ~30.87 m; a second of longitude shrinks with cos(latitude).
    const double second = 6371008.8 * M_PI / 180.0 / 3600.0;
    {
        const Heightfield hf = load_heightfield(asset("dem_squared.tif")); // 1", ~37.9 N
        EXPECT_NEAR(hf.dy, second, 0.3);
        EXPECT_NEAR(hf.dx, second * std::cos(37.9 * M_PI / 180), 0.3);
        EXPECT_NE(hf.crs.find("UTM"), std::string::npos);
    }
    {
        const Heightfield hf = load_heightfield(asset("N42E001.hgt")); // 3", 42.5 N
        EXPECT_NEAR(hf.dy, 3 * second, 1.0);
        EXPECT_NEAR(hf.dx, 3 * second * std::cos(42.5 * M_PI / 180), 1.0);
        // UTM zone 31N has its central meridian at 3 E (easting 500 km): the SW corner (1 E, 42 N)
        // lies 2 degrees of longitude west of it; northing is the meridian arc to 42 N.
        EXPECT_NEAR(hf.origin_x, 500000 - 2 * 3600 * second * std::cos(42 * M_PI / 180), 2000);
        // Meridian arc of the WGS 84 ellipsoid to 42 N, times the UTM scale factor 0.9996.
        const double a = 6378137.0, e2 = 0.00669438, phi = 42 * M_PI / 180;
        const double arc = a * ((1 - e2 / 4 - 3 * e2 * e2 / 64) * phi -
                                (3 * e2 / 8 + 3 * e2 * e2 / 32) * std::sin(2 * phi) +
                                15 * e2 * e2 / 256 * std::sin(4 * phi));
        EXPECT_NEAR(hf.origin_y, 0.9996 * arc, 2000);
    }
}

TEST(Raster, UngeoreferencedRasterUsesCellAndZscale) {
    LoadOptions options;
    options.cell = 2.5;
    options.zscale = 0.5;
    const Heightfield hf = load_heightfield(asset("crater_u16.png"), options);
    EXPECT_DOUBLE_EQ(hf.dx, 2.5);
    EXPECT_DOUBLE_EQ(hf.dy, 2.5);
    EXPECT_NEAR(hf.min_z(), 1533.f * 0.5f, 1e-3);
    EXPECT_NEAR(hf.max_z(), 2478.f * 0.5f, 1e-3);
}

// A GeoTIFF placed by a model transformation (tag 34264) instead of a tie point and a pixel
// scale is the same raster when the matrix is north up; rotated, or placed by ground control
// points alone, it is refused. Before, both were read as rasters without georeferencing: 1 m
// cells for 30 m ones.
TEST(Raster, ModelTransformationPlacesTheRasterAsATiePointDoes) {
    const std::string dir = tinlod::test::temp_dir();
    const auto load = [&](const std::string &name,
                          const std::vector<std::pair<unsigned, std::vector<double>>> &georef) {
        // GeoKeys: model projected, raster pixel-is-area, EPSG:32631 (UTM zone 31N).
        const std::string path = dir + "/" + name;
        std::ofstream(path, std::ios::binary) << tinlod::test::geotiff_bytes(
            georef, {1, 1, 0, 3, 1024, 0, 1, 1, 1025, 0, 1, 1, 3072, 0, 1, 32631});
        return load_heightfield(path);
    };
    const Heightfield tied = load(
        "tied.tif", {{33550, {30.0, 30.0, 0.0}}, {33922, {0.0, 0.0, 0.0, 500000.0, 4e6, 0.0}}});
    EXPECT_DOUBLE_EQ(tied.dx, 30.0);
    EXPECT_DOUBLE_EQ(tied.origin_x, 500015.0); // the SW sample's centre
    EXPECT_DOUBLE_EQ(tied.origin_y, 4e6 - 45.0);
    const Heightfield matrix = load(
        "matrix.tif", {{34264, {30.0, 0, 0, 500000.0, 0, -30.0, 0, 4e6, 0, 0, 0, 0, 0, 0, 0, 1}}});
    EXPECT_DOUBLE_EQ(matrix.dx, tied.dx);
    EXPECT_DOUBLE_EQ(matrix.dy, tied.dy);
    EXPECT_DOUBLE_EQ(matrix.origin_x, tied.origin_x);
    EXPECT_DOUBLE_EQ(matrix.origin_y, tied.origin_y);
    EXPECT_EQ(matrix.crs, tied.crs);
    EXPECT_EQ(matrix.z, tied.z);
    const double c = std::cos(0.5), s = std::sin(0.5);
    try {
        load("rotated.tif",
             {{34264,
               {30 * c, -30 * s, 0, 500000.0, -30 * s, -30 * c, 0, 4e6, 0, 0, 0, 0, 0, 0, 0, 1}}});
        ADD_FAILURE() << "a rotated raster loaded";
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find("rotated.tif: georeferenced by a rotated"),
                  std::string::npos)
            << e.what();
    }
    try {
        load("gcps.tif", {{33922, {0, 0, 0, 500000.0, 4e6, 0, 1, 1, 0, 500030.0, 4e6 - 30, 0}}});
        ADD_FAILURE() << "a raster placed by ground control points loaded";
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find("gcps.tif: georeferenced by 2 ground control points"),
                  std::string::npos)
            << e.what();
    }
}

TEST(Raster, BadFilesThrowNamingTheFile) {
    const std::string dir = tinlod::test::temp_dir();
    auto write = [&](const std::string &name, const std::string &bytes) {
        std::ofstream(dir + "/" + name, std::ios::binary) << bytes;
        return dir + "/" + name;
    };
    const std::string cases[][2] = {
        {dir + "/missing.tif", "no such file"},
        {write("empty.png", ""), "file is empty"},
        {write("short.hgt", std::string(1000, '\0')), "is not an SRTM tile"},
        {write("garbage.tif", "this is not a tiff at all"), "cannot read raster"},
    };
    for (const auto &[path, reason] : cases) {
        SCOPED_TRACE(path);
        try {
            load_heightfield(path);
            ADD_FAILURE() << "no error";
        } catch (const Error &e) {
            EXPECT_EQ(e.subject(), path);
            EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
        }
    }
}

TEST(Raster, AllVoidHgtIsRejected) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string path = dir + "/N10E010.hgt";
    std::string bytes(std::size_t(1201) * 1201 * 2, '\0');
    for (std::size_t i = 0; i < bytes.size(); i += 2)
        bytes[i] = char(0x80); // -32768 big-endian
    std::ofstream(path, std::ios::binary) << bytes;
    EXPECT_THROW(load_heightfield(path), Error);
}

// Ring k of the fill holds the voids k steps from valid samples. A tile whose south-west half is
// void fills in 1200 rings, each found from the last: rescanning every void for each ring took
// seconds here and minutes for an SRTM1 tile. A flat terrain fills with its height.
TEST(Raster, HalfVoidHgtFillsRingByRingWithItsHeight) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string path = dir + "/N10E010.hgt";
    const int n = 1201;
    std::string bytes(std::size_t(n) * n * 2, '\0');
    for (int r = 0; r < n; ++r) // file rows run north to south
        for (int c = 0; c < n; ++c) {
            const std::size_t at = 2 * (std::size_t(r) * n + c);
            bytes[at] = char(r > c ? 0x80 : 0x00); // -32768 (void) or 100, big-endian
            bytes[at + 1] = char(r > c ? 0 : 100);
        }
    std::ofstream(path, std::ios::binary) << bytes;
    const Heightfield hf = load_heightfield(path);
    EXPECT_EQ(hf.voids, std::int64_t(n) * (n - 1) / 2);
    EXPECT_EQ(hf.filled, hf.voids);
    EXPECT_EQ(hf.cropped, 0);
    for (float z : hf.z)
        ASSERT_EQ(z, 100.0f);
}
