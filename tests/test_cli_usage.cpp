// The command line says what it does: view-independent budgets (exactly the nodes asked, the error
// reached as measured), usage errors (exit 2, one `tinlod: error:` line naming the option) apart
// from bad input (exit 1), a store wherever a DEM is taken, and summaries that name their units and
// whose times add up.
#include "assets.hpp"

#include "tinlod/mesh_io.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/render.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

using tinlod::test::asset;
using tinlod::test::run_cli;

namespace fs = std::filesystem;

namespace {

nlohmann::json read_json(const std::string &path) {
    return nlohmann::json::parse(std::ifstream(path));
}

std::string quoted(const std::string &path) { return "'" + path + "'"; }

struct Measured {
    double max_vertical = 0.0;
    std::int64_t covered = 0; // samples inside some triangle (counted once each)
};

// The largest |z_sample - z_tin| over every DEM sample, sample by sample: each sample is found in
// a triangle of the mesh (xy, barycentric) and compared with the plane through its corners. Written
// here, apart from the library's measure, brute force over each triangle's bounding box.
Measured exhaustive_vertical_error(const tinlod::Heightfield &hf, const tinlod::Mesh &mesh) {
    std::vector<char> seen(std::size_t(hf.size()), 0);
    Measured m;
    for (auto f : mesh.faces()) {
        double x[3], y[3], z[3];
        int k = 0;
        for (auto v : f.vertices()) {
            const auto &p = mesh.point(v);
            // Every node stands on a sample: its lattice column and row, exactly.
            x[k] = std::round(p[0] / hf.dx);
            y[k] = std::round(p[1] / hf.dy);
            z[k] = p[2];
            ++k;
        }
        const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        const int c0 = std::max(0, int(std::floor(std::min({x[0], x[1], x[2]}))));
        const int c1 = std::min(hf.width - 1, int(std::ceil(std::max({x[0], x[1], x[2]}))));
        const int r0 = std::max(0, int(std::floor(std::min({y[0], y[1], y[2]}))));
        const int r1 = std::min(hf.height - 1, int(std::ceil(std::max({y[0], y[1], y[2]}))));
        for (int r = r0; r <= r1; ++r)
            for (int c = c0; c <= c1; ++c) {
                const double w0 = ((x[1] - c) * (y[2] - r) - (x[2] - c) * (y[1] - r)) / area;
                const double w1 = ((x[2] - c) * (y[0] - r) - (x[0] - c) * (y[2] - r)) / area;
                const double w2 = 1.0 - w0 - w1;
                if (w0 < 0.0 || w1 < 0.0 || w2 < -1e-12)
                    continue;
                const double dz =
                    std::abs(double(hf.at(c, r)) - (w0 * z[0] + w1 * z[1] + w2 * z[2]));
                m.max_vertical = std::max(m.max_vertical, dz);
                char &s = seen[std::size_t(r) * std::size_t(hf.width) + std::size_t(c)];
                m.covered += s == 0;
                s = 1;
            }
    }
    return m;
}

std::int64_t boundary_nodes(const tinlod::Mesh &mesh) {
    std::int64_t b = 0;
    for (auto v : mesh.vertices())
        b += mesh.is_boundary(v);
    return b;
}

} // namespace

// Item 8: without a camera, --max-nodes N gives exactly N nodes (greedy insertion by largest
// vertical error), --max-triangles T the budget or one under it, and the error the stats and the
// summary report is the one an independent measure of the output finds.
TEST(CliUsage, ViewIndependentBudgetKeepsExactlyThatManyNodesAndReportsTheErrorReached) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string dem = asset("dem_squared.tif");
    const tinlod::Heightfield hf = tinlod::load_heightfield(dem);
    const std::string out = dir + "/out.ply", stats = dir + "/s.json";
    const std::string base = "simplify " + quoted(dem) + " -o " + out + " --stats " + stats + " ";

    double error_at_500 = 0.0;
    for (const std::int64_t nodes : {std::int64_t(4), std::int64_t(500), std::int64_t(3000)}) {
        SCOPED_TRACE(nodes);
        const auto r = run_cli(base + "--max-nodes " + std::to_string(nodes));
        ASSERT_EQ(r.status, 0) << r.err;
        const tinlod::Mesh mesh = tinlod::read_mesh(out);
        EXPECT_EQ(std::int64_t(mesh.n_vertices()), nodes);
        const auto s = read_json(stats);
        EXPECT_EQ(s["output"]["nodes"].get<std::int64_t>(), nodes);
        EXPECT_EQ(s["simplify"]["stopped_by"], "budget");
        const Measured m = exhaustive_vertical_error(hf, mesh);
        EXPECT_EQ(m.covered, hf.size()) << "the TIN leaves samples uncovered";
        const double reported = s["error"]["max_vertical"].get<double>();
        EXPECT_NEAR(reported, m.max_vertical, 1e-4 * std::max(1.0, m.max_vertical));
        EXPECT_GT(m.max_vertical, 0.0);
        // The summary names the error in metres, not screen pixels.
        EXPECT_NE(r.out.find("max vertical error"), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("px"), std::string::npos) << r.out;
        if (nodes == 500)
            error_at_500 = m.max_vertical;
    }

    // A triangle budget: the count is the budget or one under it, and a TIN over the rectangle.
    for (const std::int64_t triangles : {std::int64_t(2), std::int64_t(999), std::int64_t(1000)}) {
        SCOPED_TRACE(triangles);
        const auto r = run_cli(base + "--max-triangles " + std::to_string(triangles));
        ASSERT_EQ(r.status, 0) << r.err;
        const tinlod::Mesh mesh = tinlod::read_mesh(out);
        const auto t = std::int64_t(mesh.n_faces());
        EXPECT_LE(t, triangles);
        EXPECT_GE(t, triangles - 1);
        EXPECT_EQ(t, 2 * std::int64_t(mesh.n_vertices()) - boundary_nodes(mesh) - 2);
        EXPECT_EQ(exhaustive_vertical_error(hf, mesh).covered, hf.size());
    }

    // A bound and a budget: whichever comes first. A bound above the error of 500 nodes stops
    // first; one below it leaves the budget to stop.
    auto r = run_cli(base + "--max-nodes 500 --max-error " + std::to_string(2.0 * error_at_500));
    ASSERT_EQ(r.status, 0) << r.err;
    auto s = read_json(stats);
    EXPECT_LT(s["output"]["nodes"].get<std::int64_t>(), 500);
    EXPECT_LE(s["error"]["max_vertical"].get<double>(), 2.0 * error_at_500);
    EXPECT_EQ(s["simplify"]["stopped_by"], "bound");
    r = run_cli(base + "--max-nodes 500 --max-error " + std::to_string(0.5 * error_at_500));
    ASSERT_EQ(r.status, 0) << r.err;
    s = read_json(stats);
    EXPECT_EQ(s["output"]["nodes"].get<std::int64_t>(), 500);
    EXPECT_EQ(s["simplify"]["stopped_by"], "budget");
    EXPECT_NE(r.out.find("budget came first"), std::string::npos) << r.out;
}

// Items 9 and 10: every kind of bad option value (empty, nan, inf, overflow, negative, out of
// range, not a number), an unknown or missing option and conflicting options are usage errors:
// exit 2, one line `tinlod: error: OPTION...`, nothing written.
TEST(CliUsage, BadOptionValuesAreUsageErrorsNamingTheOption) {
    const std::string dir = tinlod::test::temp_dir();
    const fs::path out = fs::path(dir) / "out";
    fs::create_directories(out);
    const std::string dem = quoted(asset("dem_squared.tif"));
    const std::string mesh = quoted(asset("bun_zipper_res4.ply"));
    const std::string path = quoted(asset("paths/n42_descent.csv"));
    const std::string o = " -o " + (out / "a.ply").string();
    const std::string camera = " --eye 1,1,900 --at 500,500,0";
    const std::string retrieve = "retrieve " + dem + camera + o;
    const std::string simplify = "simplify " + dem + camera + o;
    const std::string vertical = "simplify " + dem + o;
    const std::string fly = "fly " + dem + " --path " + path;
    const std::string render = "render " + dem + camera + " -o " + (out / "a.png").string();
    const std::string compare = "compare " + dem + " " + dem + camera;
    struct Case {
        std::string args, option;
    };
    const std::vector<Case> cases = {
        {retrieve + " --viewport 4294967297x1", "--viewport"},
        {retrieve + " --viewport 100000x100000", "--viewport"},
        {retrieve + " --tol ''", "--tol"},
        {retrieve + " --tol abc", "--tol"},
        {retrieve + " --tol -1", "--tol"},
        {retrieve + " --fov nan", "--fov"},
        {retrieve + " --fov 1e999", "--fov"},
        {retrieve + " --cache-mb 1e300", "--cache-mb"},
        {retrieve + " --cell nan", "--cell"},
        {retrieve + " --zscale 0", "--zscale"},
        {"retrieve " + dem + " --eye 1,1,900 --at 1,1,900" + o, "--eye/--at"},
        {"retrieve " + dem + " --eye 1,1 --at 5,5,0" + o, "--eye"},
        {retrieve + " --full", "--full"},
        {retrieve + " --bogus", "--bogus"},
        {"retrieve " + dem + camera, "--output"},
        {simplify + " --retrieve-share nan", "--retrieve-share"},
        {simplify + " --tol inf", "--tol"},
        {simplify + " --max-nodes -5", "--max-nodes"},
        {simplify + " --max-nodes 1e3", "--max-nodes"},
        {simplify + " --max-nodes 99999999999999999999", "--max-nodes"},
        {simplify + " --max-error 1", "--max-error"},
        {simplify + " --max-triangles 100", "--max-triangles"},
        {vertical + " --max-error nan", "--max-error"},
        {vertical + " --max-nodes 3", "--max-nodes"},
        {vertical + " --max-triangles 1", "--max-triangles"},
        {vertical + " --max-error 1 --tol 2", "--tol"},
        {"simplify " + mesh + o + " --max-triangles 100", "--max-triangles"},
        {fly + " --fps inf", "--fps"},
        {fly + " --tol 0", "--tol"},
        {fly + " --hysteresis nan", "--hysteresis"},
        {fly + " --retrieve-share -0.5", "--retrieve-share"},
        {fly + " --viewport 4294967297x1", "--viewport"},
        {fly + " --frames-eye nan,0,0 --frames-at 0,0,0", "--frames-eye"},
        {render + " --scalar-max nan", "--scalar-max"},
        {compare + " --threshold 300", "--threshold"},
        {compare + " --samples -1", "--samples"},
        {"--threads 0 info " + dem, "--threads"},
    };
    for (const Case &c : cases) {
        SCOPED_TRACE(c.args);
        const auto r = run_cli(c.args);
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_EQ(r.err.rfind("tinlod: error: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(c.option), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(fs::is_empty(out)) << "output written on a usage error";
    }
    // Bad input is not a usage error: a file that does not exist exits 1.
    const auto r = run_cli("info " + (out / "none.tif").string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(r.err.rfind("tinlod: error: ", 0), 0u) << r.err;
    // --help and --version print to stdout and exit 0; the help says what the statuses mean.
    const auto help = run_cli("--help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.out.find("Exit status"), std::string::npos) << help.out;
    EXPECT_EQ(run_cli("--version").status, 0);
    EXPECT_EQ(run_cli("simplify --help").status, 0);
}

// Item 9: a path whose time runs from 0 to 1e300 is refused, naming the path, before any frame
// (it overflowed the frame count into one frame and exit 0), and so is a keyframe under the
// terrain that no frame falls on.
TEST(CliUsage, FlyRefusesAPathTooLongToFly) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string path = dir + "/long.csv";
    std::ofstream(path) << "t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n"
                        << "0,10,10,900,500,500,0\n"
                        << "1e300,20,20,900,500,500,0\n";
    const auto r = run_cli("fly " + quoted(asset("dem_squared.tif")) + " --path " + path +
                           " --stats " + dir + "/f.csv");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find(path + ": the path lasts"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/f.csv"));

    // A keyframe 5 km under the terrain between two frames (4 frames a second, keyframes 0.1 s
    // apart) is refused as a frame there would be: the flight passes through it.
    const std::string under = dir + "/under.csv";
    std::ofstream(under) << "t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n"
                         << "0,500,500,900,1000,1000,0\n"
                         << "0.1,600,600,-5000,1000,1000,0\n"
                         << "0.2,600,600,900,1000,1000,0\n";
    const auto u = run_cli("fly " + quoted(asset("dem_squared.tif")) + " --path " + under +
                           " --stats " + dir + "/f.csv");
    EXPECT_EQ(u.status, 1) << u.err;
    EXPECT_NE(u.err.find(under + ": the eye (600"), std::string::npos) << u.err;
    EXPECT_NE(u.err.find("inside the terrain"), std::string::npos) << u.err;
    EXPECT_FALSE(fs::exists(dir + "/f.csv"));
}

// Item 11: a store is taken wherever a DEM is: info tells what it holds, and it reads back as the
// DEM it was built from (compare against the DEM: no vertical error; render draws it).
TEST(CliUsage, EveryCommandThatTakesADemTakesAStore) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string dem = quoted(asset("dem_squared.tif"));
    const std::string store = dir + "/s.tlq";
    ASSERT_EQ(run_cli("build " + dem + " -o " + store).status, 0);

    auto r = run_cli("info --json " + store);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto s = nlohmann::json::parse(r.out);
    r = run_cli("info --json " + dem);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto d = nlohmann::json::parse(r.out);
    EXPECT_EQ(s["kind"], "store");
    for (const char *key : {"width", "height", "min", "max", "bounds", "cell_size"})
        EXPECT_EQ(s[key], d[key]) << key;
    EXPECT_GT(s["tiles"].get<std::int64_t>(), 0);
    EXPECT_GE(s["tile_level"].get<int>(), 0);
    EXPECT_EQ(s["bytes"].get<std::int64_t>(), std::int64_t(fs::file_size(store)));

    // A store keeps the cell size it was built with.
    r = run_cli("info --cell 2 " + store);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("--cell"), std::string::npos) << r.err;

    std::string why;
    if (!tinlod::render_available(&why))
        GTEST_SKIP() << "no OpenGL context for render and compare: " << why;
    const std::string camera = " --eye -10,-10,900 --at 1000,1000,0 --viewport 160x90";
    r = run_cli("compare --json " + store + " " + dem + camera);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto c = nlohmann::json::parse(r.out);
    EXPECT_EQ(c["geometry"]["max_vertical"].get<double>(), 0.0);
    EXPECT_EQ(c["geometry"]["uncovered"].get<std::int64_t>(), 0);
    EXPECT_TRUE(c["image"]["identical"].get<bool>());
    r = run_cli("render " + store + camera + " --color error --reference " + store + " -o " + dir +
                "/a.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GT(fs::file_size(dir + "/a.png"), 0u);
}

// Item 15: the summaries name what they measured, their times add up to the stages that ran
// (conversion included, each in the stats' time_ms), a mesh's stats claim no DEM stage, and
// `info` prints its keys in reading order with named bounds.
TEST(CliUsage, SummariesNameTheirUnitsAndTheirTimesAddUp) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string dem = quoted(asset("dem_squared.tif"));
    const std::string stats = dir + "/s.json";
    // "in T ms (a x, b y, ...)": the parts, which must add up to T (each rounded to 1 ms).
    const std::regex summary(R"( in (\d+) ms \(([^)]*)\))");
    const auto check_times = [&](const std::string &out, const nlohmann::json &times) {
        std::smatch m;
        ASSERT_TRUE(std::regex_search(out, m, summary)) << out;
        const double total = std::stod(m[1]);
        double sum = 0.0;
        std::size_t parts = 0;
        const std::string list = m[2];
        const std::regex part(R"(([a-z ()]+) (\d+))");
        for (auto it = std::sregex_iterator(list.begin(), list.end(), part);
             it != std::sregex_iterator(); ++it) {
            sum += std::stod((*it)[2]);
            ++parts;
        }
        EXPECT_EQ(parts + 1, times.size()) << out << times.dump(); // the stages and "total"
        EXPECT_NEAR(sum, total, 0.5 * double(parts) + 1.0) << out;
        double json_sum = 0.0;
        for (const auto &[stage, ms] : times.items())
            if (stage != "total")
                json_sum += ms.get<double>();
        EXPECT_NEAR(json_sum, total, 1.0) << out << times.dump();
        EXPECT_NEAR(times["total"].get<double>(), total, 1.0) << out << times.dump();
    };

    auto r = run_cli("retrieve " + dem + " --eye 1,1,900 --at 500,500,0 -o " + dir +
                     "/r.ply --stats " + stats);
    ASSERT_EQ(r.status, 0) << r.err;
    auto s = read_json(stats);
    EXPECT_TRUE(s["time_ms"].contains("convert")) << s["time_ms"].dump();
    check_times(r.out, s["time_ms"]);

    r = run_cli("simplify " + dem + " --max-error 5 -o " + dir + "/v.ply --stats " + stats);
    ASSERT_EQ(r.status, 0) << r.err;
    s = read_json(stats);
    check_times(r.out, s["time_ms"]);
    EXPECT_EQ(r.out.find("px"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" m"), std::string::npos) << r.out;
    EXPECT_TRUE(s["error"]["max_screen_px"].is_null()) << s["error"].dump();

    r = run_cli("simplify " + quoted(asset("bun_zipper_res4.ply")) +
                " --eye 0,-1,0.2 --at 0,0,0.1 -o " + dir + "/m.ply --stats " + stats);
    ASSERT_EQ(r.status, 0) << r.err;
    s = read_json(stats);
    EXPECT_FALSE(s.contains("retrieve")) << "a mesh's stats name a DEM stage: " << s.dump();
    check_times(r.out, s["time_ms"]);

    r = run_cli("info " + dem);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.rfind("file: ", 0), 0u) << r.out;
    const std::regex bounds(R"(\nbounds: xmin \S+ ymin \S+ zmin \S+ xmax \S+ ymax \S+ zmax \S+\n)");
    EXPECT_TRUE(std::regex_search(r.out, bounds)) << r.out;
    EXPECT_LT(r.out.find("\nwidth: "), r.out.find("\nbounds: "));
}
