// The tile build cut into jobs (`tinlod tiles --plan`, `--part`, `--layer-only`) and spread over a
// Dask cluster (python/tinlod_dask): the parts, run in any order, again, or killed and run again,
// and the Dask build, with or without a worker killed midway, give the single-process build's tile
// set byte for byte.
#include "assets.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using tinlod::test::asset;
using tinlod::test::run_cli;
using tinlod::test::temp_dir;

namespace {

std::string slurp(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// Every file under `dir` (hidden ones too), by its path inside it, with its bytes.
std::map<std::string, std::string> tree(const std::string &dir) {
    std::map<std::string, std::string> files;
    for (const auto &f : fs::recursive_directory_iterator(dir))
        if (f.is_regular_file())
            files[fs::relative(f.path(), dir).string()] = slurp(f.path().string());
    return files;
}

// The files of two trees that differ or are in one only.
std::vector<std::string> differences(const std::map<std::string, std::string> &a,
                                     const std::map<std::string, std::string> &b) {
    std::vector<std::string> out;
    for (const auto &[name, bytes] : a)
        if (!b.count(name) || b.at(name) != bytes)
            out.push_back(name);
    for (const auto &[name, bytes] : b)
        if (!a.count(name))
            out.push_back(name);
    return out;
}

// The pyramid every test builds: the bundled SRTM tile to level 10 (84 tiles, about a second on
// one thread), with normals.
const std::string k_levels = " --max-zoom 10 --normals";

// The DEM in single quotes for the shell (appended piece by piece: GCC 12 warns, -Wrestrict, a
// false positive, on the inlined `"'" + std::string`).
std::string dem() {
    std::string q = "'";
    q += asset("N42E001.hgt");
    q += "'";
    return q;
}

// The single-process build, made once.
const std::map<std::string, std::string> &whole_run() {
    static const std::map<std::string, std::string> files = [] {
        const std::string dir = temp_dir() + "/whole";
        const auto r = run_cli("--threads 1 tiles " + dem() + " -o " + dir + k_levels);
        EXPECT_EQ(r.status, 0) << r.err;
        return tree(dir);
    }();
    return files;
}

// The jobs of a cut at level `cut`, from `tinlod tiles --plan`: the tiles of level `cut` above any
// tile written on the levels from there (each with its subtree), and top:cut.
std::vector<std::string> jobs(int cut) {
    const auto r = run_cli("tiles " + dem() + " -o unused --plan" + k_levels);
    EXPECT_EQ(r.status, 0) << r.err;
    const auto plan = nlohmann::json::parse(r.out);
    std::set<std::pair<std::int64_t, std::int64_t>> roots;
    for (const auto &level : plan["levels"]) {
        const int z = level["z"];
        if (z < cut)
            continue;
        for (const auto &rect : level["available"])
            for (std::int64_t y = rect["startY"]; y <= rect["endY"].get<std::int64_t>(); ++y)
                for (std::int64_t x = rect["startX"]; x <= rect["endX"].get<std::int64_t>(); ++x)
                    roots.insert({x >> (z - cut), y >> (z - cut)});
    }
    std::vector<std::string> parts = {"top:" + std::to_string(cut)};
    for (const auto &[x, y] : roots)
        parts.push_back(std::to_string(cut) + "/" + std::to_string(x) + "/" + std::to_string(y));
    return parts;
}

} // namespace

TEST(TilesParts, PartsInAnyOrderAndRunTwiceMakeTheWholeRunsTileSet) {
    const std::string dir = temp_dir() + "/parts";
    std::vector<std::string> parts = jobs(8);
    ASSERT_GT(parts.size(), 3u);
    // Backwards (the deep subtrees first), and the first subtree again at the end, as a retry.
    std::reverse(parts.begin(), parts.end());
    parts.push_back(parts.front());
    for (const std::string &part : parts) {
        const auto r =
            run_cli("--threads 1 tiles " + dem() + " -o " + dir + k_levels + " --part " + part);
        ASSERT_EQ(r.status, 0) << part << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir + "/layer.json")) << part << " wrote layer.json";
    }
    const auto r = run_cli("tiles " + dem() + " -o " + dir + k_levels + " --layer-only");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto &whole = whole_run();
    ASSERT_GT(whole.size(), 80u);
    EXPECT_EQ(differences(whole, tree(dir)), std::vector<std::string>{});
}

TEST(TilesParts, KilledPartLeavesWholeTilesAndItsRerunCompletesTheSet) {
    const std::string dir = temp_dir() + "/parts";
    const auto &whole = whole_run();
    // The levels above 10 hold 35 tiles: killed once its first tile is in, midway.
    const pid_t pid =
        tinlod::test::start_cli({"--threads", "1", "tiles", asset("N42E001.hgt"), "-o", dir,
                                 "--max-zoom", "10", "--normals", "--part", "top:10"});
    bool killed = false;
    for (int i = 0; i < 20000 && !killed; ++i) {
        if (fs::exists(dir + "/0/1/0.terrain")) {
            kill(pid, SIGKILL);
            killed = true;
        }
        usleep(500);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(killed) << "the part finished before a tile was in";
    int tiles = 0;
    for (const auto &[name, bytes] : tree(dir))
        if (fs::path(name).extension() == ".terrain") {
            ++tiles;
            EXPECT_TRUE(whole.count(name) && whole.at(name) == bytes) << name << " is not whole";
        }
    EXPECT_GT(tiles, 0);
    // Run again, then the subtrees of level 9 and layer.json: the whole set, and the killed run's
    // temporaries gone.
    for (const std::string &part : jobs(9)) {
        const auto r =
            run_cli("--threads 1 tiles " + dem() + " -o " + dir + k_levels + " --part " + part);
        ASSERT_EQ(r.status, 0) << part << ": " << r.err;
    }
    ASSERT_EQ(run_cli("tiles " + dem() + " -o " + dir + k_levels + " --layer-only").status, 0);
    EXPECT_EQ(differences(whole, tree(dir)), std::vector<std::string>{});
}

TEST(TilesParts, PartOutsideTheLevelsIsAUsageError) {
    const std::string dir = temp_dir() + "/parts";
    for (const std::string spec : {"11/0/0", "8/0/256", "8/512/0", "top:0", "top:12", "8/1", "x"}) {
        const auto r = run_cli("tiles " + dem() + " -o " + dir + k_levels + " --part " + spec);
        EXPECT_EQ(r.status, 2) << spec;
        EXPECT_NE(r.err.find("--part"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(fs::exists(dir + "/0"));
}
