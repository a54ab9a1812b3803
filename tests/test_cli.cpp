// Foundation: the command line on real files and on bad input (one error line naming the file,
// non-zero exit, no partial output).
#include "assets.hpp"

#include "tinlod/mesh_io.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

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
    for (const char* key : {"load", "retrieve", "write"})
        EXPECT_TRUE(stats["time_ms"].contains(key)) << key;
    EXPECT_GT(stats["peak_rss_mb"].get<double>(), 0.0);
    const tinlod::Mesh mesh = tinlod::read_mesh(dir + "/full.ply");
    EXPECT_EQ(mesh.n_faces(), std::size_t(2 * 335 * 458));
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
    auto write = [&](const std::string& name, const std::string& bytes) {
        std::ofstream(in / name, std::ios::binary) << bytes;
        return (in / name).string();
    };
    std::string hgt(std::size_t(1201) * 1201 * 2, '\0');
    const std::string truncated_tif = [&] {
        std::ifstream src(asset("dem_srtm30.tif"), std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(src)), {});
        return write("truncated.tif", bytes.substr(0, bytes.size() / 3));
    }();
    // A TIFF header declaring a 46000 x 46000 float raster, with no samples behind it.
    const std::string huge_tif = [&] {
        std::string b = "II*";
        b += '\0';
        auto u16 = [&](unsigned v) { b += char(v & 255), b += char(v >> 8); };
        auto u32 = [&](unsigned v) { u16(v & 0xffff), u16(v >> 16); };
        u32(8);
        const unsigned entries[][3] = {{256, 4, 46000}, {257, 4, 46000}, {258, 3, 32}, {259, 3, 1},
                                       {262, 3, 1},     {273, 4, 8},     {277, 3, 1},  {278, 4, 46000},
                                       {279, 4, 4000000000u}, {339, 3, 3}};
        u16(10);
        for (const auto& e : entries) {
            u16(e[0]), u16(e[1]), u32(1);
            e[1] == 3 ? (u16(e[2]), u16(0)) : u32(e[2]);
        }
        u32(0);
        return write("huge.tif", b);
    }();
    const std::vector<BadCase> cases = {
        {"absurd raster size", "info " + huge_tif, huge_tif},
        {"missing", "retrieve --full " + (in / "nope.tif").string() + " -o {out}/a.ply", "no such file"},
        {"empty", "retrieve --full " + write("empty.tif", "") + " -o {out}/a.ply", "file is empty"},
        {"garbage", "retrieve --full " + write("garbage.png", "not a png") + " -o {out}/a.ply",
         "cannot read raster"},
        {"truncated", "retrieve --full " + truncated_tif + " -o {out}/a.ply", truncated_tif},
        {"hgt size", "retrieve --full " + write("N00E000.hgt", hgt.substr(0, 5000)) + " -o {out}/a.ply",
         "not an SRTM tile"},
        {"missing folder", "retrieve --full " + asset("dem_squared.tif") + " -o {out}/no/such/a.ply",
         "does not exist"},
        {"bad extension", "retrieve --full " + asset("dem_squared.tif") + " -o {out}/a.xyz",
         "unknown mesh format"},
        {"mesh garbage", "info " + write("bad.ply", "ply\nformat ascii 1.0\nelement vertex 99\n"),
         "bad.ply"},
        {"absurd mesh count",
         "info " + write("huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3000000000\n"
                                     "property float x\nproperty float y\nproperty float z\n"
                                     "end_header\n"),
         "declares 3000000000"},
        // Found by fuzz_mesh: OpenMesh's PLY reader spins forever on this format line.
        {"malformed PLY format", "info " + write("spin.ply", "ply\nformat ascii \3311.0\nelement vertex 3\n"
                                                             "property float x\nend_header\n0\n0\n0\n"),
         "unknown format"},
        {"absurd OFF count", "info " + write("huge.off", "OFF\n300000000 1 0\n0 0 0\n"), "declares 300000000"},
        {"NaN camera", "retrieve " + asset("dem_squared.tif") + " --eye nan,0,0 --at 1,1,1 -o {out}/a.ply",
         "--eye: coordinates must be finite"},
        {"eye inside the terrain",
         "simplify " + asset("dem_squared.tif") + " --eye 1500,1500,100 --at 1,1,1 -o {out}/a.ply",
         "inside the terrain"},
        {"eye on the look-at point",
         "retrieve " + asset("dem_squared.tif") + " --eye 1,1,900 --at 1,1,900 -o {out}/a.ply", "coincide"},
        {"negative tau", "retrieve " + asset("dem_squared.tif") + " --eye 1,1,900 --at 9,9,0 --tol -1 -o {out}/a.ply",
         "--tol"},
        {"zero tau in flight",
         "fly " + asset("dem_squared.tif") + " --path " + asset("paths/n42_descent.csv") + " --tol 0 --stats {out}/f.csv",
         "--tol"},
        {"missing path", "fly " + asset("dem_squared.tif") + " --path " + (in / "none.csv").string() + " --stats {out}/f.csv",
         "cannot open camera path"},
        {"bad path", "fly " + asset("dem_squared.tif") + " --path " + write("bad.csv", "t,x\n") + " --stats {out}/f.csv",
         "expected the header"},
        {"bad cell", "info --cell -1 " + asset("crater_u16.png"), "--cell"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        std::string args = c.args;
        for (auto pos = args.find("{out}"); pos != std::string::npos; pos = args.find("{out}"))
            args.replace(pos, 5, out.string());
        const auto r = run_cli(args);
        EXPECT_NE(r.status, 0);
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        // One line: the message ends with the only newline.
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(fs::is_empty(out)) << "partial output left behind";
    }
}
