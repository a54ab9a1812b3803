// Foundation: the command line on real files and on bad input (one error line naming the file,
// non-zero exit, no partial output).
#include "assets.hpp"

#include "tinlod/mesh_io.hpp"
#include "tinlod/render.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

using tinlod::test::asset;
using tinlod::test::run_cli;

namespace fs = std::filesystem;

TEST(Cli, InfoReportsRasterAndMeshAsJson) {
    auto r = run_cli("info --json '" + asset("dem_squared.tif") + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["width"], 129);
    EXPECT_EQ(j["height"], 129);
    EXPECT_EQ(j["voids"], 0);
    ASSERT_EQ(j["bounds"].size(), 6u);
    // Bounds span the grid: (width-1) cells east at the reported cell size.
    EXPECT_NEAR(j["bounds"][3].get<double>(), 128 * j["cell_size"][0].get<double>(), 1e-6);

    r = run_cli("info --json '" + asset("bun_zipper_res2.ply") + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto m = nlohmann::json::parse(r.out);
    EXPECT_EQ(m["faces"], 16301);            // MANIFEST
    EXPECT_EQ(m["non_manifold_edges"], 150); // MANIFEST
    EXPECT_GT(m["boundary_edges"].get<int>(), 0);
}

TEST(Cli, RetrieveFullWritesGridTinAndStats) {
    const std::string dir = tinlod::test::temp_dir();
    auto r = run_cli("retrieve '" + asset("crater_u16.png") + "' --full -o " + dir +
                     "/full.ply --stats " + dir + "/stats.json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(std::ifstream(dir + "/stats.json"));
    EXPECT_EQ(stats["input"]["nodes"], 336 * 459);
    EXPECT_EQ(stats["output"]["nodes"], 336 * 459);
    EXPECT_EQ(stats["output"]["triangles"], 2 * 335 * 458);
    for (const char *key : {"load", "retrieve", "write"})
        EXPECT_TRUE(stats["time_ms"].contains(key)) << key;
    EXPECT_GT(stats["peak_rss_mb"].get<double>(), 0.0);
    const tinlod::Mesh mesh = tinlod::read_mesh(dir + "/full.ply");
    EXPECT_EQ(mesh.n_faces(), std::size_t(2 * 335 * 458));
}

// simplify on a DEM: retrieval, then erase; the error the command measures at every sample stays
// within the bound with or without the retrieval, and with a node budget beside the bound.
TEST(Cli, SimplifyDemRetrievesThenErasesWithinTheBound) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string base = "simplify '" + asset("dem_squared.tif") +
                             "' --eye -10,-10,500 --at 100,100,0 -o " + dir + "/out.ply --stats " +
                             dir + "/stats.json ";
    std::int64_t nodes[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
        auto r = run_cli(base + (k == 0 ? "--tol 1" : "--tol 1 --retrieve-share 0"));
        ASSERT_EQ(r.status, 0) << r.err;
        const auto stats = nlohmann::json::parse(std::ifstream(dir + "/stats.json"));
        EXPECT_LE(stats["error"]["max_screen_px"].get<double>(), 1.0);
        nodes[k] = stats["output"]["nodes"].get<std::int64_t>();
        if (k == 0) {
            EXPECT_LT(stats["retrieve"]["nodes"], stats["input"]["nodes"]);
        } else {
            EXPECT_EQ(stats["retrieve"]["nodes"], stats["input"]["nodes"]);
        }
    }
    EXPECT_NEAR(double(nodes[0]), double(nodes[1]), 0.05 * double(nodes[1]));
    auto r = run_cli(base + "--tol 0.5 --max-nodes 100");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(std::ifstream(dir + "/stats.json"));
    EXPECT_LE(stats["error"]["max_screen_px"].get<double>(), 0.5);
    EXPECT_GT(stats["output"]["nodes"].get<std::int64_t>(), 100);
}

// simplify --max-error on a DEM: greedy insertion first where the bound is coarse, the full grid
// with --retrieve-share 0; the vertical error the command measures at every sample stays within the
// bound either way.
TEST(Cli, SimplifyMaxErrorStartsFromGreedyInsertionWithinTheBound) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string base = "simplify '" + asset("dem_srtm30.tif") + "' --max-error 40 -o " + dir +
                             "/out.ply --stats " + dir + "/stats.json ";
    for (const std::string stage : {"greedy", "grid"}) {
        auto r = run_cli(base + (stage == "grid" ? "--retrieve-share 0" : ""));
        ASSERT_EQ(r.status, 0) << r.err;
        const auto stats = nlohmann::json::parse(std::ifstream(dir + "/stats.json"));
        EXPECT_EQ(stats["retrieve"]["first_stage"], stage);
        EXPECT_LE(stats["error"]["max_vertical"].get<double>(), 40.0);
        EXPECT_LT(stats["output"]["nodes"], stats["retrieve"]["nodes"]);
    }
}

struct BadCase {
    std::string name;
    std::string args; // {dir} is the temp folder
    std::string message;
};

TEST(Cli, BadInputGetsOneLineNamingTheProblemAndNoOutput) {
    const std::string dir = tinlod::test::temp_dir();
    const fs::path in = fs::path(dir) / "in";
    const fs::path out = fs::path(dir) / "out";
    fs::create_directories(in);
    fs::create_directories(out);
    auto write = [&](const std::string &name, const std::string &bytes) {
        std::ofstream(in / name, std::ios::binary) << bytes;
        return (in / name).string();
    };
    std::string hgt(std::size_t(1201) * 1201 * 2, '\0');
    const std::string truncated_tif = [&] {
        std::ifstream src(asset("dem_srtm30.tif"), std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(src)), {});
        return write("truncated.tif", bytes.substr(0, bytes.size() / 3));
    }();
    // The last bytes cut off: OpenImageIO 2.4 read the float TIFF's last strips as zeros and
    // reported success, and libpng printed a line of its own beside tinlod's for the PNG.
    const auto cut = [&](const std::string &name, std::size_t bytes) {
        std::ifstream src(asset(name), std::ios::binary);
        std::string data((std::istreambuf_iterator<char>(src)), {});
        return write("cut_" + name, data.substr(0, data.size() - bytes));
    };
    const std::string cut_tif = cut("dem_squared.tif", 5000), cut_png = cut("crater_u16.png", 1000);
    // A TIFF header declaring a 46000 x 46000 float raster, with no samples behind it.
    const std::string huge_tif = [&] {
        std::string b = "II*";
        b += '\0';
        auto u16 = [&](unsigned v) { b += char(v & 255), b += char(v >> 8); };
        auto u32 = [&](unsigned v) { u16(v & 0xffff), u16(v >> 16); };
        u32(8);
        const unsigned entries[][3] = {
            {256, 4, 46000}, {257, 4, 46000}, {258, 3, 32},    {259, 3, 1},           {262, 3, 1},
            {273, 4, 8},     {277, 3, 1},     {278, 4, 46000}, {279, 4, 4000000000u}, {339, 3, 3}};
        u16(10);
        for (const auto &e : entries) {
            u16(e[0]), u16(e[1]), u32(1);
            e[1] == 3 ? (u16(e[2]), u16(0)) : u32(e[2]);
        }
        u32(0);
        return write("huge.tif", b);
    }();
    // A 2x2 int16 GeoTIFF in EPSG:4326: pixel scale (dx, dy) degrees, NW corner at (lon, lat).
    auto geographic_tif = [&](const std::string &name, double dx, double dy, double lon,
                              double lat) {
        // GeoKeys: model geographic, raster pixel-is-area, EPSG:4326.
        return write(name, tinlod::test::geotiff_bytes(
                               {{33550, {dx, dy, 0.0}}, {33922, {0.0, 0.0, 0.0, lon, lat, 0.0}}},
                               {1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326}));
    };
    // Found by fuzz_mesh: OpenMesh takes a face's vertex count as given (32 GB for this one).
    const std::string ply_face_header =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n";
    std::string binary_off = "OFF BINARY\n";
    for (unsigned char c : {3, 0, 0, 0, 0xff, 0xff, 0xff, 0x7f, 0, 0, 0, 0})
        binary_off += char(c);
    const std::vector<BadCase> cases = {
        {"absurd raster size", "info " + huge_tif, huge_tif},
        {"missing", "retrieve --full " + (in / "nope.tif").string() + " -o {out}/a.ply",
         "no such file"},
        {"empty", "retrieve --full " + write("empty.tif", "") + " -o {out}/a.ply", "file is empty"},
        {"garbage", "retrieve --full " + write("garbage.png", "not a png") + " -o {out}/a.ply",
         "cannot read raster"},
        {"truncated", "retrieve --full " + truncated_tif + " -o {out}/a.ply", truncated_tif},
        {"float TIFF without its last strips", "retrieve --full " + cut_tif + " -o {out}/a.ply",
         cut_tif + ": cannot read samples (truncated or corrupt)"},
        {"PNG without its last bytes", "retrieve --full " + cut_png + " -o {out}/a.ply",
         cut_png + ": cannot read samples (truncated or corrupt)"},
        {"hgt size",
         "retrieve --full " + write("N00E000.hgt", hgt.substr(0, 5000)) + " -o {out}/a.ply",
         "not an SRTM tile"},
        {"missing folder",
         "retrieve --full " + asset("dem_squared.tif") + " -o {out}/no/such/a.ply",
         "does not exist"},
        // Every output is checked before the work: a second output's missing folder left the
        // first output written.
        {"missing stats folder",
         "simplify " + asset("dem_squared.tif") +
             " --eye 1,1,900 --at 500,500,0 -o {out}/a.ply --stats {out}/no/s.json",
         "{out}/no/s.json: output folder"},
        {"missing depth folder",
         "render " + asset("dem_squared.tif") +
             " --eye 1,1,900 --at 500,500,0 -o {out}/a.png --depth {out}/no/d.exr",
         "{out}/no/d.exr: output folder"},
        {"bad extension", "retrieve --full " + asset("dem_squared.tif") + " -o {out}/a.xyz",
         "unknown mesh format"},
        {"mesh garbage", "info " + write("bad.ply", "ply\nformat ascii 1.0\nelement vertex 99\n"),
         "bad.ply"},
        {"absurd mesh count",
         "info " + write("huge.ply",
                         "ply\nformat binary_little_endian 1.0\nelement vertex 3000000000\n"
                         "property float x\nproperty float y\nproperty float z\n"
                         "end_header\n"),
         "declares 3000000000"},
        // Found by fuzz_mesh: OpenMesh's PLY reader spins forever on this format line.
        {"malformed PLY format",
         "info " + write("spin.ply", "ply\nformat ascii \3311.0\nelement vertex 3\n"
                                     "property float x\nend_header\n0\n0\n0\n"),
         "unknown format"},
        {"absurd OFF count", "info " + write("huge.off", "OFF\n300000000 1 0\n0 0 0\n"),
         "declares 300000000"},
        {"PLY face of 4e9 vertices",
         "info " + write("face.ply", ply_face_header + "4000000000 0 1 2\n"), "malformed PLY body"},
        // Found by fuzz_mesh: once a value fails to parse, OpenMesh loops on with stale counts.
        {"PLY face not a number", "info " + write("word.ply", ply_face_header + "three 0 1 2\n"),
         "malformed PLY body: face 0"},
        {"OFF face of 4e9 vertices",
         "info " + write("face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n"),
         "malformed OFF: face 0"},
        {"binary OFF count", "info " + write("binary.off", binary_off),
         "header declares 3 vertices but the file holds only 23 bytes"},
        // Found by fuzz_mesh: OpenMesh's OBJ reader aborts on a face vertex without a position.
        {"OBJ face vertex without a position",
         "info " + write("nopos.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf /2 3 1\n"),
         "face vertex '/2' has no position index"},
        // Found by fuzz_raster (UBSan): a longitude of 1e17 degrees overflowed the UTM zone.
        {"longitude off the Earth", "info " + geographic_tif("lon.tif", 0.01, 0.01, 1e17, 40.0),
         "not on Earth"},
        {"infinite pixel scale",
         "info " +
             geographic_tif("scale.tif", std::numeric_limits<double>::infinity(), 0.01, 1.0, 40.0),
         "georeferencing is not finite"},
        {"NaN camera",
         "retrieve " + asset("dem_squared.tif") + " --eye nan,0,0 --at 1,1,1 -o {out}/a.ply",
         "--eye: coordinates must be finite"},
        {"eye inside the terrain",
         "simplify " + asset("dem_squared.tif") + " --eye 1500,1500,100 --at 1,1,1 -o {out}/a.ply",
         "inside the terrain"},
        {"eye on the look-at point",
         "retrieve " + asset("dem_squared.tif") + " --eye 1,1,900 --at 1,1,900 -o {out}/a.ply",
         "coincide"},
        {"negative tau",
         "retrieve " + asset("dem_squared.tif") +
             " --eye 1,1,900 --at 9,9,0 --tol -1 -o {out}/a.ply",
         "--tol"},
        {"infinite tau",
         "simplify " + asset("dem_squared.tif") +
             " --eye 1,1,900 --at 9,9,0 --tol inf -o {out}/a.ply",
         "--tol: must be a finite number >= 0"},
        {"zero tau in flight",
         "fly " + asset("dem_squared.tif") + " --path " + asset("paths/n42_descent.csv") +
             " --tol 0 --stats {out}/f.csv",
         "--tol"},
        {"missing path",
         "fly " + asset("dem_squared.tif") + " --path " + (in / "none.csv").string() +
             " --stats {out}/f.csv",
         "cannot open camera path"},
        {"bad path",
         "fly " + asset("dem_squared.tif") + " --path " + write("bad.csv", "t,x\n") +
             " --stats {out}/f.csv",
         "expected the header"},
        {"fixed camera without its target",
         "fly " + asset("dem_squared.tif") + " --path " + asset("paths/n42_descent.csv") +
             " --frames {out} --frames-eye 1,1,900 --stats {out}/f.csv",
         "--frames-eye: give both --frames-eye and --frames-at"},
        {"fixed camera without frames",
         "fly " + asset("dem_squared.tif") + " --path " + asset("paths/n42_descent.csv") +
             " --frames-eye 1,1,900 --frames-at 9,9,0 --stats {out}/f.csv",
         "give --frames DIR"},
        {"meshes folder under a file",
         "fly " + asset("dem_squared.tif") + " --path " + asset("paths/n42_descent.csv") +
             " --meshes " + asset("dem_squared.tif") + "/none --stats {out}/f.csv",
         "dem_squared.tif' is not a folder"},
        {"bad cell", "info --cell -1 " + asset("crater_u16.png"), "--cell"},
    };
    for (const auto &c : cases) {
        SCOPED_TRACE(c.name);
        std::string args = c.args;
        for (auto pos = args.find("{out}"); pos != std::string::npos; pos = args.find("{out}"))
            args.replace(pos, 5, out.string());
        std::string message = c.message;
        if (const auto at = message.find("{out}"); at != std::string::npos)
            message.replace(at, 5, out.string());
        const auto r = run_cli(args);
        EXPECT_NE(r.status, 0);
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
        // One line: the message ends with the only newline.
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(fs::is_empty(out)) << "partial output left behind";
    }
}

// A write that fails partway (a full disk; here a file-size limit of 16 KiB, which fails each
// write past it with EFBIG) is an error naming the file, with no file left: OpenMesh's and
// OpenImageIO's file writers report success with a short file (a 100 KiB PLY, PNG or TIFF passed as
// whole before tinlod checked its own streams).
TEST(Cli, AWriteThatRunsOutOfRoomIsAnErrorAndLeavesNoFile) {
    const fs::path out = tinlod::test::temp_dir();
    const std::string dem = "'" + asset("dem_squared.tif") + "'";
    const std::string camera = " --eye 1,1,900 --at 500,500,0 --viewport 320x180";
    struct Case {
        std::string args, file;
    };
    std::vector<Case> cases;
    for (const std::string ext : {"ply", "obj", "off", "stl"})
        cases.push_back({"retrieve --full " + dem + " -o {file}", "grid." + ext});
    for (const std::string ext : {"png", "tif", "exr"})
        cases.push_back({"render " + dem + camera + " -o {file}", "frame." + ext});
    cases.push_back({"build " + dem + " -o {file}", "store.tlq"});
    std::string why;
    const bool drawn = tinlod::render_available(&why);
    for (const Case &c : cases) {
        if (!drawn && c.args.rfind("render", 0) == 0)
            continue;
        SCOPED_TRACE(c.file);
        const std::string file = (out / c.file).string();
        std::string args = c.args;
        args.replace(args.find("{file}"), 6, file);
        // Within the limit the same command writes the file whole, larger than the limit.
        ASSERT_EQ(run_cli(args).status, 0);
        ASSERT_GT(fs::file_size(file), 16u << 10);
        fs::remove_all(out);
        fs::create_directory(out);
        const auto r = run_cli(args, 16u << 10);
        EXPECT_NE(r.status, 0);
        EXPECT_NE(r.err.find(file + ": cannot write"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(file)) << "a short file left behind";
        fs::remove_all(out);
        fs::create_directory(out);
    }
    if (!drawn)
        GTEST_SKIP() << "no OpenGL context for the render cases: " << why;
}

static std::string read_bytes(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

TEST(Cli, ThreadsIsValidatedAndLeavesTheOutputUnchanged) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string dem = "'" + asset("dem_squared.tif") + "'";
    // Before or after the subcommand; refused before any work, as a usage error.
    for (const std::string &args : {"--threads 0 build " + dem + " -o " + dir + "/zero.tlq",
                                    "build " + dem + " -o " + dir + "/zero.tlq --threads two",
                                    "build " + dem + " -o " + dir + "/zero.tlq --threads 5000"}) {
        SCOPED_TRACE(args);
        const auto r = run_cli(args);
        EXPECT_EQ(r.status, 2);
        EXPECT_NE(r.err.find("--threads: must be a whole number from 1 to 1024"), std::string::npos)
            << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(dir + "/zero.tlq"));
    }
    // The build splits rows of nodes over the threads: one thread writes the same bytes.
    auto r = run_cli("build " + dem + " -o " + dir + "/all.tlq --stats " + dir + "/all.json");
    ASSERT_EQ(r.status, 0) << r.err;
    r = run_cli("--threads 1 build " + dem + " -o " + dir + "/one.tlq --stats " + dir +
                "/one.json");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir + "/one.json"))["threads"], 1);
    EXPECT_GE(nlohmann::json::parse(std::ifstream(dir + "/all.json"))["threads"].get<int>(), 1);
    const std::string all = read_bytes(dir + "/all.tlq");
    EXPECT_GT(all.size(), 0u);
    EXPECT_TRUE(all == read_bytes(dir + "/one.tlq")) << "--threads 1 changed the store";
}

TEST(Cli, RetrieveFromAStoreKeepsAtMostCacheMbOfTiles) {
    const std::string dir = tinlod::test::temp_dir();
    ASSERT_EQ(run_cli("build '" + asset("dem_squared.tif") + "' -o " + dir + "/s.tlq").status, 0);
    // tau = 0 reads every tile of the store.
    auto retrieve = [&](const std::string &cache) {
        const auto r = run_cli("retrieve " + dir + "/s.tlq --eye 100,100,400 --at 1500,2000,100 " +
                               "--tol 0 --cache-mb " + cache + " -o " + dir + "/t.ply --stats " +
                               dir + "/t.json");
        EXPECT_EQ(r.status, 0) << r.err;
        return nlohmann::json::parse(std::ifstream(dir + "/t.json"))["store"];
    };
    const auto none = retrieve("0");
    EXPECT_EQ(none["tiles_read"], none["tiles_total"]);
    EXPECT_EQ(none["tiles_resident"], 0);
    EXPECT_EQ(none["tiles_evicted"], none["tiles_read"]);
    const auto all = retrieve("256");
    EXPECT_EQ(all["tiles_read"], all["tiles_total"]);
    EXPECT_EQ(all["tiles_resident"], all["tiles_read"]);
    EXPECT_EQ(all["tiles_evicted"], 0);
}
