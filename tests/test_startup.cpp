// A program that starts at once (issue #50): the command line loads a library only when a command
// or a file needs it, seen in the dynamic loader's own report (LD_DEBUG=files); and the faster
// paths that make this possible (libpng and libtiff for plain rasters, WGS 84 to UTM without PROJ)
// give exactly what OpenImageIO and PROJ give.
#include "assets.hpp"

#include "../lib/src/backends/backends.hpp"
#include "../lib/src/crs.hpp"
#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"

#include <gtest/gtest.h>
#include <png.h>
#include <proj.h>
#include <tiffio.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <sys/wait.h>

using tinlod::test::asset;

namespace fs = std::filesystem;
namespace backends = tinlod::backends;

namespace {

struct Loaded {
    int status = -1;
    std::string out;
    std::vector<std::string> objects; // every shared object the dynamic loader mapped
    bool any(const std::string &pattern) const {
        const std::regex re(pattern, std::regex::icase);
        return std::any_of(objects.begin(), objects.end(),
                           [&](const std::string &o) { return std::regex_search(o, re); });
    }
};

std::string slurp(const fs::path &p) {
    std::ostringstream s;
    s << std::ifstream(p, std::ios::binary).rdbuf();
    return s.str();
}

// Runs `program` (the CLI unless given) with `args` under LD_DEBUG=files: the objects are the
// loader's "file=NAME [namespace];  generating link map" lines, one per object it maps, at start
// or by dlopen.
Loaded run_loaded(const std::string &args, const std::string &program = TINLOD_CLI) {
    const fs::path dir = tinlod::test::temp_dir();
    const std::string cmd = "LD_DEBUG=files timeout 120 '" + program + "' " + args + " >'" +
                            (dir / "out").string() + "' 2>'" + (dir / "err").string() + "'";
    const int raw = std::system(cmd.c_str());
    Loaded l;
    l.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    l.out = slurp(dir / "out");
    std::istringstream err(slurp(dir / "err"));
    const std::regex mapped(R"(file=(\S+) \[\d+\];\s+generating link map)");
    for (std::string line; std::getline(err, line);) {
        std::smatch m;
        if (std::regex_search(line, m, mapped))
            l.objects.push_back(m[1]);
    }
    return l;
}

// What no command that neither draws nor reads an image file through OpenImageIO may load.
const char *const k_heavy = "OpenImageIO|libEGL|libGL|libOpenGL|gdal|libproj|tinlod_oiio";

std::string listing(const Loaded &l) {
    std::string s;
    for (const auto &o : l.objects)
        s += o + "\n";
    return s;
}

TEST(Startup, VersionAndInfoOnSmallFilesLoadAFewLibrariesAndNothingHeavy) {
    // tinlod --version mapped 264 shared objects (OpenImageIO's plugin tree, PROJ with curl and
    // sqlite, EGL and GL) before issue #50.
    for (const std::string &args :
         {std::string("--version"), "info " + asset("N42E001.hgt"),
          "info " + asset("bun_zipper_res4.ply"), "info --json " + asset("N42E001.hgt")}) {
        SCOPED_TRACE(args);
        const Loaded l = run_loaded(args);
        EXPECT_EQ(l.status, 0);
        EXPECT_FALSE(l.any(k_heavy)) << listing(l);
        EXPECT_FALSE(l.any("tinlod_|libtiff|libpng")) << listing(l);
        EXPECT_LE(l.objects.size(), 15u) << listing(l);
        EXPECT_FALSE(l.objects.empty()) << "no LD_DEBUG report to check";
    }
    // The .hgt's place is still interpreted: WGS 84 to its UTM zone, as PROJ would.
    EXPECT_NE(run_loaded("info " + asset("N42E001.hgt")).out.find("EPSG:32631 (UTM zone 31N"),
              std::string::npos);
}

TEST(Startup, RastersLoadOnlyTheReaderTheirFormatNeeds) {
    // A WGS 84 GeoTIFF: libtiff's module, no OpenImageIO and no PROJ.
    const Loaded tif = run_loaded("info " + asset("dem_srtm30.tif"));
    EXPECT_EQ(tif.status, 0);
    EXPECT_TRUE(tif.any("tinlod_tiff\\.so")) << listing(tif);
    EXPECT_FALSE(tif.any(k_heavy)) << listing(tif);
    // A 16-bit PNG: libpng's module alone.
    const Loaded png = run_loaded("info " + asset("crater_u16.png"));
    EXPECT_EQ(png.status, 0);
    EXPECT_TRUE(png.any("tinlod_png\\.so")) << listing(png);
    EXPECT_FALSE(png.any(k_heavy)) << listing(png);
    EXPECT_FALSE(png.any("libtiff")) << listing(png);
    // A NAD83 GeoTIFF needs PROJ's datum transformations: PROJ is loaded then, and only then.
    const Loaded nad83 = run_loaded("info " + asset("dem_squared.tif"));
    EXPECT_EQ(nad83.status, 0);
    EXPECT_TRUE(nad83.any("libproj")) << listing(nad83);
    EXPECT_FALSE(nad83.any("OpenImageIO|libEGL")) << listing(nad83);
}

TEST(Startup, SimplifyOfAnHgtLoadsNothingHeavyAndRenderLoadsWhatItDraws) {
    const std::string dir = tinlod::test::temp_dir();
    const Loaded simplify =
        run_loaded("simplify " + asset("N42E001.hgt") + " --max-error 20 -o " + dir + "/tin.ply");
    EXPECT_EQ(simplify.status, 0);
    EXPECT_TRUE(fs::exists(dir + "/tin.ply"));
    EXPECT_FALSE(simplify.any(k_heavy)) << listing(simplify);
    EXPECT_LE(simplify.objects.size(), 15u) << listing(simplify);
    std::string why;
    if (!tinlod::render_available(&why))
        GTEST_SKIP() << "no OpenGL context: " << why;
    const Loaded render =
        run_loaded("render " + asset("bun_zipper_res4.ply") +
                   " --eye 0,0.1,0.4 --at 0,0.1,0 --viewport 64x48 -o " + dir + "/frame.png");
    EXPECT_EQ(render.status, 0);
    EXPECT_TRUE(render.any("libEGL")) << listing(render);
    EXPECT_TRUE(render.any("tinlod_oiio\\.so")) << listing(render);
    const tinlod::Image frame = tinlod::read_image(dir + "/frame.png");
    EXPECT_EQ(frame.width, 64);
    EXPECT_EQ(frame.height, 48);
}

TEST(Startup, AMissingModuleIsOneErrorLineNamingIt) {
    // The program copied without lib/tinlod beside it: commands that need no module still run.
    const fs::path bin = fs::path(tinlod::test::temp_dir()) / "bin";
    fs::create_directories(bin);
    fs::copy_file(TINLOD_CLI, bin / "tinlod");
    const std::string program = (bin / "tinlod").string();
    EXPECT_EQ(run_loaded("info " + asset("N42E001.hgt"), program).status, 0);
    const fs::path dir = tinlod::test::temp_dir();
    const std::string cmd = "'" + program + "' info " + asset("crater_u16.png") +
                            " >/dev/null 2>'" + (dir / "err").string() + "'";
    const int raw = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(raw));
    EXPECT_EQ(WEXITSTATUS(raw), 1);
    const std::string err = slurp(dir / "err");
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_EQ(err.rfind("tinlod: error: ", 0), 0u) << err;
    EXPECT_NE(err.find("tinlod_png.so: tinlod's module for PNG is missing"), std::string::npos)
        << err;
}

// --- The faster paths against what they replace. ---

// WGS 84 to UTM against PROJ's own transformation, to the last bit, in every zone and both
// hemispheres, inside the zones and far outside them (where the projection's domain ends).
TEST(Startup, Wgs84ToUtmIsBitForBitProjs) {
    PJ_CONTEXT *ctx = proj_context_create();
    proj_log_level(ctx, PJ_LOG_NONE);
    std::mt19937_64 random(50);
    std::uniform_real_distribution<double> near(-3.5, 3.5), far(-170, 170), lat(-84, 84);
    int compared = 0, outside = 0;
    for (int zone = 1; zone <= 60; ++zone)
        for (const bool south : {false, true}) {
            const std::string to = "EPSG:" + std::to_string((south ? 32700 : 32600) + zone);
            PJ *raw = proj_create_crs_to_crs(ctx, "EPSG:4326", to.c_str(), nullptr);
            PJ *pj = proj_normalize_for_visualization(ctx, raw);
            proj_destroy(raw);
            ASSERT_NE(pj, nullptr) << to;
            const double centre = -183 + 6 * zone;
            for (int i = 0; i < 200; ++i) {
                const double lon = centre + (i % 4 == 3 ? far(random) : near(random));
                const double la = i == 0 ? 0.0 : i == 1 ? 90.0 : lat(random);
                const PJ_COORD p = proj_trans(pj, PJ_FWD, proj_coord(lon, la, 0, 0));
                const auto q = tinlod::crs::wgs84_to_utm(zone, south, lon, la);
                EXPECT_EQ(std::memcmp(&p.xy.x, &q[0], 8), 0) << to << " " << lon << " " << la;
                EXPECT_EQ(std::memcmp(&p.xy.y, &q[1], 8), 0) << to << " " << lon << " " << la;
                ++compared;
                outside += !std::isfinite(q[0]);
            }
            proj_destroy(pj);
        }
    proj_context_destroy(ctx);
    EXPECT_EQ(compared, 60 * 2 * 200);
    EXPECT_GT(outside, 0); // the far points include some beyond the domain
}

// The CRS checks tinlod answers itself are PROJ's answers.
TEST(Startup, KnownCrsChecksAgreeWithProj) {
    const std::string path = "x.tif";
    for (const int epsg : {4326, 32601, 32631, 32660, 32701, 32760})
        for (const bool geographic : {true, false}) {
            std::string ours, projs;
            try {
                tinlod::crs::check(path, epsg, geographic);
            } catch (const tinlod::Error &e) {
                ours = e.what();
            }
            try {
                backends::tinlod_proj_backend()->check_crs(path, epsg, geographic);
            } catch (const tinlod::Error &e) {
                projs = e.what();
            }
            EXPECT_EQ(ours, projs) << epsg << (geographic ? " geographic" : " projected");
        }
}

// Reads `path` through `fast` (nullptr: declined) and through OpenImageIO: the same layout, and
// the same samples when the fast reader takes it. `written` (unless empty) are the samples the
// file holds; `openimageio_reads_them` false where OpenImageIO 2.4 reads others.
bool same_as_openimageio(const std::string &path, backends::RasterFile *fast,
                         const std::vector<unsigned char> &written = {},
                         bool openimageio_reads_them = true) {
    if (fast == nullptr)
        return false;
    const auto oiio = backends::tinlod_oiio_backend()->open_raster(path);
    const backends::RasterSpec &a = fast->spec(), &b = oiio->spec();
    EXPECT_EQ(a.width, b.width) << path;
    EXPECT_EQ(a.height, b.height) << path;
    EXPECT_EQ(a.depth, b.depth) << path;
    EXPECT_EQ(a.channels, b.channels) << path;
    EXPECT_EQ(a.alpha, b.alpha) << path;
    EXPECT_EQ(int(a.type), int(b.type)) << path;
    EXPECT_EQ(a.type_bytes, b.type_bytes) << path;
    EXPECT_EQ(a.type_name, b.type_name) << path;
    EXPECT_EQ(a.mixed_types, b.mixed_types) << path;
    const std::size_t bytes = std::size_t(b.width) * b.height * b.channels * b.type_bytes;
    std::vector<unsigned char> x(bytes, 0xa5), y(bytes, 0x5a);
    if (!fast->read(a.type, x.data()))
        return false;
    EXPECT_TRUE(oiio->read(b.type, y.data())) << path;
    if (openimageio_reads_them) {
        EXPECT_TRUE(x == y) << path << ": the samples differ from OpenImageIO's";
    }
    if (!written.empty()) {
        EXPECT_TRUE(x == written) << path << ": the samples differ from the file's";
    }
    return true;
}

template <typename T> std::vector<T> pattern(int w, int h, int channels, std::mt19937 &random) {
    std::vector<T> v(std::size_t(w) * h * channels);
    std::uniform_int_distribution<int> bits(0, 255);
    for (auto &x : v) {
        unsigned char raw[sizeof(T)];
        for (auto &c : raw)
            c = static_cast<unsigned char>(bits(random));
        std::memcpy(&x, raw, sizeof(T));
        if constexpr (std::is_floating_point_v<T>)
            if (!std::isfinite(x))
                x = T(0.5);
    }
    return v;
}

struct TiffCase {
    std::uint16_t bits, format, compression, predictor;
    bool tiled;
    std::uint32_t rows_per_strip;
};

// Writes a w x h TIFF of random samples; returns them.
std::vector<unsigned char> write_tiff(const std::string &path, const TiffCase &c, int w, int h,
                                      std::mt19937 &random) {
    TIFF *tif = TIFFOpen(path.c_str(), "w");
    EXPECT_NE(tif, nullptr);
    if (tif == nullptr)
        return {};
    TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, w);
    TIFFSetField(tif, TIFFTAG_IMAGELENGTH, h);
    TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, c.bits);
    TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT, c.format);
    TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(tif, TIFFTAG_COMPRESSION, c.compression);
    if (c.predictor != PREDICTOR_NONE)
        TIFFSetField(tif, TIFFTAG_PREDICTOR, c.predictor);
    const std::size_t bytes = c.bits / 8;
    std::vector<unsigned char> data(std::size_t(w) * h * bytes);
    if (c.format == SAMPLEFORMAT_IEEEFP && c.bits == 32) {
        const auto v = pattern<float>(w, h, 1, random);
        std::memcpy(data.data(), v.data(), data.size());
    } else if (c.format == SAMPLEFORMAT_IEEEFP) {
        const auto v = pattern<double>(w, h, 1, random);
        std::memcpy(data.data(), v.data(), data.size());
    } else {
        const auto v = pattern<unsigned char>(w, h * int(bytes), 1, random);
        std::memcpy(data.data(), v.data(), data.size());
    }
    if (c.tiled) {
        const std::uint32_t tw = 16, th = 32;
        TIFFSetField(tif, TIFFTAG_TILEWIDTH, tw);
        TIFFSetField(tif, TIFFTAG_TILELENGTH, th);
        std::vector<unsigned char> tile(tw * th * bytes);
        for (std::uint32_t y = 0; y < std::uint32_t(h); y += th)
            for (std::uint32_t x = 0; x < std::uint32_t(w); x += tw) {
                std::fill(tile.begin(), tile.end(), 0);
                for (std::uint32_t r = 0; r < th && y + r < std::uint32_t(h); ++r)
                    std::memcpy(&tile[r * tw * bytes], &data[((y + r) * w + x) * bytes],
                                std::min<std::size_t>(tw, w - x) * bytes);
                TIFFWriteTile(tif, tile.data(), x, y, 0, 0);
            }
    } else {
        TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, c.rows_per_strip);
        for (int r = 0; r < h; ++r)
            TIFFWriteScanline(tif, &data[std::size_t(r) * w * bytes], std::uint32_t(r), 0);
    }
    TIFFClose(tif);
    return data;
}

TEST(Startup, PlainTiffsReadAsOpenImageIOReadsThem) {
    std::mt19937 random(7);
    const std::string dir = tinlod::test::temp_dir();
    const std::pair<std::uint16_t, std::uint16_t> types[] = {
        {8, SAMPLEFORMAT_UINT},    {8, SAMPLEFORMAT_INT},    {16, SAMPLEFORMAT_UINT},
        {16, SAMPLEFORMAT_INT},    {32, SAMPLEFORMAT_UINT},  {32, SAMPLEFORMAT_INT},
        {32, SAMPLEFORMAT_IEEEFP}, {64, SAMPLEFORMAT_IEEEFP}};
    const std::uint16_t compressions[] = {COMPRESSION_NONE,          COMPRESSION_LZW,
                                          COMPRESSION_ADOBE_DEFLATE, COMPRESSION_PACKBITS,
                                          COMPRESSION_ZSTD,          COMPRESSION_LZMA};
    int taken = 0, k = 0;
    for (const auto &[bits, format] : types)
        for (const std::uint16_t compression : compressions)
            for (const bool tiled : {false, true}) {
                const bool floating = format == SAMPLEFORMAT_IEEEFP;
                const std::uint16_t predictor =
                    compression == COMPRESSION_NONE || compression == COMPRESSION_PACKBITS
                        ? PREDICTOR_NONE
                    : k % 2 == 0 ? PREDICTOR_NONE
                    : floating   ? PREDICTOR_FLOATINGPOINT
                                 : PREDICTOR_HORIZONTAL;
                const TiffCase c{bits,      format, compression,
                                 predictor, tiled,  std::uint32_t(1 + k % 7)};
                const std::string path = dir + "/t" + std::to_string(k++) + ".tif";
                const auto written = write_tiff(path, c, 37, 45, random);
                const auto file = backends::tinlod_tiff_backend()->open(path);
                ASSERT_NE(file, nullptr) << path;
                const auto fast = file->raster();
                EXPECT_NE(fast, nullptr) << path << ": a plain TIFF declined";
                // OpenImageIO 2.4.7 reads tiled float64 TIFFs as zeros.
                taken += same_as_openimageio(path, fast.get(), written, !(tiled && bits == 64));
            }
    EXPECT_EQ(taken, k);
    // The bundled GeoTIFFs too.
    for (const char *name : {"dem_srtm30.tif", "dem_squared.tif"}) {
        const auto file = backends::tinlod_tiff_backend()->open(asset(name));
        ASSERT_NE(file, nullptr);
        const auto fast = file->raster();
        EXPECT_TRUE(same_as_openimageio(asset(name), fast.get())) << name;
    }
}

TEST(Startup, PngsReadAsOpenImageIOReadsThem) {
    // Every colour type and bit depth, with and without a tRNS key: libpng's expansions give
    // OpenImageIO's channels and samples.
    std::mt19937 random(11);
    const std::string dir = tinlod::test::temp_dir();
    struct PngCase {
        int color_type, bit_depth;
        bool trns;
    };
    std::vector<PngCase> cases;
    for (const int depth : {1, 2, 4, 8, 16})
        for (const bool trns : {false, true}) {
            cases.push_back({PNG_COLOR_TYPE_GRAY, depth, trns});
            if (depth <= 8)
                cases.push_back({PNG_COLOR_TYPE_PALETTE, depth, trns});
            if (depth >= 8) {
                cases.push_back({PNG_COLOR_TYPE_RGB, depth, trns});
                if (!trns) {
                    cases.push_back({PNG_COLOR_TYPE_GRAY_ALPHA, depth, false});
                    cases.push_back({PNG_COLOR_TYPE_RGB_ALPHA, depth, false});
                }
            }
        }
    int k = 0;
    for (const PngCase &c : cases) {
        const int w = 19, h = 13;
        const std::string path = dir + "/p" + std::to_string(k++) + ".png";
        std::FILE *f = std::fopen(path.c_str(), "wb");
        ASSERT_NE(f, nullptr);
        png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
        png_infop info = png_create_info_struct(png);
        ASSERT_EQ(setjmp(png_jmpbuf(png)), 0);
        png_init_io(png, f);
        png_set_IHDR(png, info, w, h, c.bit_depth, c.color_type, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        const int max = (1 << c.bit_depth) - 1;
        if (c.color_type == PNG_COLOR_TYPE_PALETTE) {
            png_color palette[16];
            for (int i = 0; i < 16; ++i)
                palette[i] = {png_byte(i * 16), png_byte(255 - i * 8), png_byte(i * 3)};
            png_set_PLTE(png, info, palette, std::min(max + 1, 16));
        }
        if (c.trns) {
            png_byte alpha[2] = {0, 128};
            png_color_16 key{};
            key.gray = png_uint_16(max / 2);
            key.red = key.green = key.blue = png_uint_16(max / 2);
            png_set_tRNS(png, info, alpha, c.color_type == PNG_COLOR_TYPE_PALETTE ? 2 : 0, &key);
        }
        png_write_info(png, info);
        const int channels = png_get_channels(png, info);
        const std::size_t row_bytes = png_get_rowbytes(png, info);
        // Palette indices stay within the palette; the first pixel is the tRNS key.
        const int top = c.color_type == PNG_COLOR_TYPE_PALETTE ? std::min(max, 15) : max;
        std::uniform_int_distribution<int> sample(0, top);
        std::vector<png_byte> row(row_bytes);
        for (int r = 0; r < h; ++r) {
            // Samples packed big-endian, as the file stores them.
            std::fill(row.begin(), row.end(), 0);
            for (int i = 0; i < w * channels; ++i) {
                const unsigned v = unsigned(r == 0 && i < channels ? top / 2 : sample(random));
                if (c.bit_depth == 16)
                    row[2 * i] = png_byte(v >> 8), row[2 * i + 1] = png_byte(v & 255);
                else if (c.bit_depth == 8)
                    row[i] = png_byte(v);
                else
                    row[std::size_t(i * c.bit_depth / 8)] |=
                        png_byte(v << (8 - c.bit_depth - (i * c.bit_depth) % 8));
            }
            png_write_row(png, row.data());
        }
        png_write_end(png, nullptr);
        png_destroy_write_struct(&png, &info);
        std::fclose(f);
        const auto fast = backends::tinlod_png_backend()->open_raster(path);
        EXPECT_TRUE(same_as_openimageio(path, fast.get()))
            << path << ": colour type " << c.color_type << ", " << c.bit_depth << " bits";
    }
    EXPECT_TRUE(same_as_openimageio(
        asset("crater_u16.png"),
        backends::tinlod_png_backend()->open_raster(asset("crater_u16.png")).get()));
    EXPECT_TRUE(same_as_openimageio(
        asset("fuji.png"), backends::tinlod_png_backend()->open_raster(asset("fuji.png")).get()));
}

// A key directory libgeotiff refuses (a newer version, a key pointing past the values) gives no
// GeoKeys, so the raster is projected of unknown CRS, as libgeotiff read it; a good one is WGS 84.
TEST(Startup, GeoKeysReadAsLibgeotiffReadsThem) {
    const std::string dir = tinlod::test::temp_dir();
    const auto load = [&](const std::vector<unsigned> &keys) {
        const std::string path = dir + "/k" + std::to_string(keys.size()) + "_" +
                                 std::to_string(keys[0]) + "_" + std::to_string(keys.back()) +
                                 ".tif";
        std::ofstream(path, std::ios::binary) << tinlod::test::geotiff_bytes(
            {{33550, {0.01, 0.01, 0.0}}, {33922, {0.0, 0.0, 0.0, 2.0, 45.0, 0.0}}}, keys);
        return tinlod::load_heightfield(path).crs;
    };
    // Version 1, two keys: geographic (1024 = 2), WGS 84 (2048 = 4326).
    EXPECT_EQ(load({1, 1, 0, 2, 1024, 0, 1, 2, 2048, 0, 1, 4326}),
              "EPSG:32631 (UTM zone 31N, from EPSG:4326 degrees)");
    // KeyDirectoryVersion 2: libgeotiff's GTIFNew fails.
    EXPECT_EQ(load({2, 1, 0, 2, 1024, 0, 1, 2, 2048, 0, 1, 4326}), "projected (unknown EPSG)");
    // A key in the entry itself with a count of 2.
    EXPECT_EQ(load({1, 1, 0, 2, 1024, 0, 2, 2, 2048, 0, 1, 4326}), "projected (unknown EPSG)");
    // A key in GeoDoubleParams, which the file lacks.
    EXPECT_EQ(load({1, 1, 0, 2, 1024, 0, 1, 2, 2057, 34736, 1, 0}), "projected (unknown EPSG)");
    // A key in a tag libgeotiff does not know.
    EXPECT_EQ(load({1, 1, 0, 2, 1024, 0, 1, 2, 2048, 33550, 1, 0}), "projected (unknown EPSG)");
    // A user-defined geographic CRS is taken as WGS 84.
    EXPECT_EQ(load({1, 1, 0, 2, 1024, 0, 1, 2, 2048, 0, 1, 32767}),
              "EPSG:32631 (UTM zone 31N, from EPSG:4326 degrees)");
}

} // namespace
