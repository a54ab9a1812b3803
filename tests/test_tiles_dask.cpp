// The tile build cut into jobs (`tinlod tiles --plan`, `--part`, `--layer-only`) and spread over a
// Dask cluster (python/tinlod_dask): the parts, run in any order, again, or killed and run again,
// and the Dask build, with or without a worker killed midway, give the single-process build's tile
// set byte for byte.
#include "assets.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using tinlod::test::asset;
using tinlod::test::file_bytes;
using tinlod::test::files_under;
using tinlod::test::run_cli;
using tinlod::test::temp_dir;

namespace {

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
        return files_under(dir);
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

// Debian's interpreter, the one python3-distributed installs Dask into (a python3 earlier on PATH,
// pyenv's, does not see it).
const char *const k_python = "/usr/bin/python3";

bool dask_installed() {
    const std::string check = std::string(k_python) + " -c 'import distributed' 2>/dev/null";
    return std::system(check.c_str()) == 0;
}

// A process started in a process group of its own, its stdout and stderr to `log`, with
// PYTHONPATH at the repository's python/. Destroyed, it kills its whole group (SIGKILL) and reaps
// it: a test that fails midway leaves nothing running (a Dask worker's own processes and the
// tinlod jobs they run included).
class Process {
  public:
    Process(const std::vector<std::string> &argv, const std::string &log) {
        const std::string python = (fs::path(TINLOD_MESHES_DIR).parent_path() / "python").string();
        pid_ = fork();
        if (pid_ == 0) {
            setpgid(0, 0);
            const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            dup2(fd, 1);
            dup2(fd, 2);
            setenv("PYTHONPATH", python.c_str(), 1);
            std::vector<char *> args;
            for (const std::string &a : argv)
                args.push_back(const_cast<char *>(a.c_str()));
            args.push_back(nullptr);
            execv(args[0], args.data());
            _exit(127);
        }
        setpgid(pid_, pid_); // also here: the group exists before kill() may need it
    }
    ~Process() { kill(); }
    Process(const Process &) = delete;
    Process &operator=(const Process &) = delete;

    void kill() {
        if (pid_ <= 0)
            return;
        killpg(pid_, SIGKILL);
        if (!reaped_)
            waitpid(pid_, nullptr, 0);
        pid_ = 0;
    }
    // The exit status, or -1 when it still runs after `seconds` (or was killed by a signal).
    int wait(double seconds) {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (std::chrono::steady_clock::now() < end) {
            int status = 0;
            if (waitpid(pid_, &status, WNOHANG) == pid_) {
                reaped_ = true;
                return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
            }
            usleep(20000);
        }
        return -1;
    }

  private:
    pid_t pid_ = 0;
    bool reaped_ = false;
};

// Waits up to `seconds` for `path` to hold `text`.
bool wait_for(const std::string &path, const std::string &text, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
        if (file_bytes(path).find(text) != std::string::npos)
            return true;
        usleep(20000);
    }
    return false;
}

// `python3 -m tinlod_dask tiles` of the tests' pyramid into `out`, on `where` (--scheduler ADDRESS
// or --local N), its stderr to `log`.
std::vector<std::string> dask_build(const std::string &out, const std::vector<std::string> &where,
                                    const std::string &tinlod = TINLOD_CLI) {
    std::vector<std::string> argv = {
        k_python, "-m",         "tinlod_dask", "tiles",     asset("N42E001.hgt"), "-o",
        out,      "--max-zoom", "10",          "--normals", "--tinlod",           tinlod};
    argv.insert(argv.end(), where.begin(), where.end());
    return argv;
}

std::string log_of(const std::string &path) { return path + ":\n" + file_bytes(path); }

// An executable shell script at `path` standing in for tinlod: `--plan` and `--layer-only` go to
// the real one; a `--part SPEC` job appends SPEC to `path`.jobs, then runs `part` (shell code that
// sees SPEC in $spec and the real binary in $tinlod).
void write_stand_in(const std::string &path, const std::string &part) {
    std::ofstream(path) << "#!/bin/sh\n"
                        << "tinlod='" << TINLOD_CLI << "'\n"
                        << "spec=\n"
                        << "prev=\n"
                        << "for a in \"$@\"; do [ \"$prev\" = --part ] && spec=$a; prev=$a; done\n"
                        << "[ -z \"$spec\" ] && exec \"$tinlod\" \"$@\"\n"
                        << "echo \"$spec\" >> '" << path << ".jobs'\n"
                        << part << "\n";
    fs::permissions(path, fs::perms::owner_all);
}

// The lines of a file, counted.
std::map<std::string, int> line_counts(const std::string &path) {
    std::map<std::string, int> counts;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);)
        ++counts[line];
    return counts;
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
    EXPECT_EQ(differences(whole, files_under(dir)), std::vector<std::string>{});
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
    for (const auto &[name, bytes] : files_under(dir))
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
    EXPECT_EQ(differences(whole, files_under(dir)), std::vector<std::string>{});
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

// A real scheduler and two workers on 127.0.0.1: the build through them, then a second build with
// one worker killed (SIGKILL, its whole process group: as a machine that goes down) once the first
// job reports, both equal to the single-process build, every file and layer.json; and a job that
// fails for good ends the build with the tool's error line, the folder as it was.
TEST(TilesDask, BuildOnASchedulerWithAndWithoutAKilledWorkerEqualsTheSingleProcessBuild) {
    if (!dask_installed())
        FAIL() << k_python << " has no Dask: run scripts/setup.sh (python3-distributed)";
    const std::string dir = temp_dir();
    const std::string address_file = dir + "/scheduler.json";
    // Port 0: the scheduler takes a free port and writes its address into the file.
    Process scheduler({k_python, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                       "--port", "0", "--no-dashboard", "--scheduler-file", address_file},
                      dir + "/scheduler.log");
    ASSERT_TRUE(wait_for(address_file, "tcp://", 60)) << log_of(dir + "/scheduler.log");
    const std::string address = nlohmann::json::parse(file_bytes(address_file))["address"];
    std::vector<std::unique_ptr<Process>> workers;
    for (int k = 0; k < 2; ++k)
        workers.push_back(std::make_unique<Process>(
            std::vector<std::string>{k_python, "-m", "distributed.cli.dask_worker", address,
                                     "--nthreads", "1", "--no-dashboard", "--host", "127.0.0.1",
                                     "--name", "w" + std::to_string(k),
                                     // Its scratch space in the test's folder: a killed
                                     // worker's lock is not left in /tmp/dask-worker-space.
                                     "--local-directory", dir + "/space" + std::to_string(k)},
            dir + "/worker" + std::to_string(k) + ".log"));
    for (int k = 0; k < 2; ++k) {
        const std::string log = dir + "/worker" + std::to_string(k) + ".log";
        ASSERT_TRUE(wait_for(log, "Registered to", 60)) << log_of(log);
    }
    const auto &whole = whole_run();

    {
        Process build(dask_build(dir + "/dask", {"--scheduler", address}), dir + "/build.log");
        ASSERT_EQ(build.wait(90), 0) << log_of(dir + "/build.log");
        EXPECT_EQ(differences(whole, files_under(dir + "/dask")), std::vector<std::string>{});
    }
    {
        Process build(dask_build(dir + "/killed", {"--scheduler", address}), dir + "/killed.log");
        ASSERT_TRUE(wait_for(dir + "/killed.log", "tinlod_dask: 1/", 60))
            << log_of(dir + "/killed.log");
        workers[0]->kill();
        ASSERT_EQ(build.wait(90), 0) << log_of(dir + "/killed.log");
        EXPECT_EQ(differences(whole, files_under(dir + "/killed")), std::vector<std::string>{});
        // The scheduler lost the worker with jobs on it, and ran them on the other one.
        const std::string log = dir + "/scheduler.log";
        ASSERT_TRUE(wait_for(log, "Remove worker", 10)) << log_of(log);
        const std::string removed = file_bytes(log).substr(file_bytes(log).find("Remove worker"));
        EXPECT_NE(removed.find("name: w0"), std::string::npos) << removed;
        EXPECT_EQ(removed.find("processing: 0>"), std::string::npos) << removed;
    }
    {
        // A job that fails on every try (a tinlod that fails one part): one line with the tool's
        // own error, status 1, and the folder as it was.
        const std::string failing = dir + "/failing.sh";
        std::ofstream(failing) << "#!/bin/sh\ncase \"$*\" in *--part*/*/*) echo \"tinlod: error: "
                                  "x.hgt: cannot read\" >&2; exit 1;; esac\nexec "
                               << TINLOD_CLI << " \"$@\"\n";
        fs::permissions(failing, fs::perms::owner_all);
        fs::create_directories(dir + "/kept");
        std::ofstream(dir + "/kept/layer.json") << "earlier";
        std::vector<std::string> argv = dask_build(dir + "/kept", {"--scheduler", address});
        argv[std::size_t(std::find(argv.begin(), argv.end(), "--tinlod") - argv.begin()) + 1] =
            failing;
        Process build(argv, dir + "/failed.log");
        EXPECT_EQ(build.wait(60), 1) << log_of(dir + "/failed.log");
        const std::string err = file_bytes(dir + "/failed.log");
        EXPECT_NE(err.find("tinlod_dask: error: part "), std::string::npos) << err;
        EXPECT_NE(err.find(": tinlod: error: x.hgt: cannot read\n"), std::string::npos) << err;
        EXPECT_EQ(files_under(dir + "/kept"),
                  (std::map<std::string, std::string>{{"layer.json", "earlier"}}));
    }
}

// `--local 2`: the same build on a local cluster the driver starts itself, each job within
// `--memory-mb 1` (its DEM read by windows).
TEST(TilesDask, BuildOnALocalClusterEqualsTheSingleProcessBuild) {
    if (!dask_installed())
        FAIL() << k_python << " has no Dask: run scripts/setup.sh (python3-distributed)";
    const std::string dir = temp_dir();
    Process build(dask_build(dir + "/local", {"--local", "2", "--memory-mb", "1"}),
                  dir + "/local.log");
    ASSERT_EQ(build.wait(90), 0) << log_of(dir + "/local.log");
    EXPECT_EQ(differences(whole_run(), files_under(dir + "/local")), std::vector<std::string>{});
}

// A job tinlod refuses with its own error line fails the same way on any worker: the run ends with
// that line after one try of the job, however many --retries (Dask retried such jobs before).
TEST(TilesDask, JobRefusedByTinlodEndsTheRunWithoutRetries) {
    if (!dask_installed())
        FAIL() << k_python << " has no Dask: run scripts/setup.sh (python3-distributed)";
    const std::string dir = temp_dir(), stand_in = dir + "/refusing-tinlod";
    write_stand_in(stand_in, "echo \"tinlod: error: $spec: refused by the stand-in\" >&2; exit 1");
    Process build(dask_build(dir + "/refused", {"--local", "1", "--retries", "3"}, stand_in),
                  dir + "/refused.log");
    ASSERT_EQ(build.wait(90), 1) << log_of(dir + "/refused.log");
    EXPECT_NE(file_bytes(dir + "/refused.log").find("refused by the stand-in"), std::string::npos)
        << log_of(dir + "/refused.log");
    const auto tries = line_counts(stand_in + ".jobs");
    ASSERT_FALSE(tries.empty());
    for (const auto &[spec, count] : tries)
        EXPECT_EQ(count, 1) << "part " << spec << " ran " << count << " times";
    EXPECT_FALSE(fs::exists(dir + "/refused"));
}

// A job whose tinlod dies (here: SIGKILL on its first try, as the kernel's OOM killer would) runs
// again, and the set is the single-process build's.
TEST(TilesDask, JobWhoseTinlodDiesRunsAgain) {
    if (!dask_installed())
        FAIL() << k_python << " has no Dask: run scripts/setup.sh (python3-distributed)";
    const std::string dir = temp_dir(), stand_in = dir + "/dying-tinlod";
    write_stand_in(stand_in, "mark='" + dir +
                                 "/died-'$(echo \"$spec\" | tr / _)\n"
                                 "[ -e \"$mark\" ] || { touch \"$mark\"; kill -KILL $$; }\n"
                                 "exec \"$tinlod\" \"$@\"");
    Process build(dask_build(dir + "/died", {"--local", "1", "--cut-zoom", "8"}, stand_in),
                  dir + "/died.log");
    ASSERT_EQ(build.wait(120), 0) << log_of(dir + "/died.log");
    const auto tries = line_counts(stand_in + ".jobs");
    ASSERT_FALSE(tries.empty());
    for (const auto &[spec, count] : tries)
        EXPECT_EQ(count, 2) << "part " << spec << " ran " << count << " times";
    EXPECT_EQ(differences(whole_run(), files_under(dir + "/died")), std::vector<std::string>{});
}
