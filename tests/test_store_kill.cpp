// Nothing lost: a `tinlod build` killed at any moment leaves the previous store (or none), never a
// half-written one that opens.
#include "assets.hpp"

#include "tinlod/error.hpp"
#include "tinlod/store.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

using namespace tinlod;

// The temporaries in a folder whose name starts with `prefix`.
static std::vector<std::string> temporaries(const std::string &dir, const std::string &prefix) {
    std::vector<std::string> names;
    for (const auto &e : std::filesystem::directory_iterator(dir))
        if (e.path().filename().string().rfind(prefix, 0) == 0)
            names.push_back(e.path().filename().string());
    return names;
}

// Starts a build of the large tile into `store` (stderr to `err` unless empty) and sends it
// `signal` once its temporary is in the store's folder: the build's pid, or 0 when it finished
// before (the caller tries again).
static pid_t signal_while_writing(const std::string &store, int signal,
                                  const std::string &err = "") {
    namespace fs = std::filesystem;
    const std::string dir = fs::path(store).parent_path().string();
    const std::string prefix = "." + fs::path(store).filename().string() + ".tinlod-";
    const pid_t pid =
        tinlod::test::start_cli({"build", tinlod::test::asset("N42E001.hgt"), "-o", store}, err);
    for (int i = 0; i < 20000; ++i) {
        if (!temporaries(dir, prefix).empty()) {
            kill(pid, signal);
            return pid;
        }
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid)
            return 0;
        usleep(500);
    }
    return 0;
}

TEST(StoreKill, KilledBuildLeavesThePreviousStoreOrTheNewOneWhole) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string store = dir + "/terrain.tlq";
    // The previous store: a small DEM. The build that gets killed writes a larger one over it.
    ASSERT_EQ(
        tinlod::test::run_cli("build " + tinlod::test::asset("dem_squared.tif") + " -o " + store)
            .status,
        0);
    int previous = 0, replaced = 0;
    for (int delay_ms : {0, 5, 20, 40, 60, 80, 100, 150, 200, 300, 500}) {
        SCOPED_TRACE(delay_ms);
        const pid_t pid =
            tinlod::test::start_cli({"build", tinlod::test::asset("N42E001.hgt"), "-o", store});
        ASSERT_GT(pid, 0);
        usleep(useconds_t(delay_ms) * 1000);
        kill(pid, SIGKILL);
        int status = 0;
        waitpid(pid, &status, 0);
        // Whatever the moment, the store at the path opens and is one of the two, whole.
        TileStore opened(store);
        const int w = opened.frame().width;
        ASSERT_TRUE(w == 129 || w == 1201) << w;
        EXPECT_NO_THROW(opened.heightfield()); // every tile's checksum holds
        (w == 129 ? previous : replaced) += 1;
        if (w == 1201) { // start again from the small store for the next round
            const auto r = tinlod::test::run_cli("build " + tinlod::test::asset("dem_squared.tif") +
                                                 " -o " + store);
            ASSERT_EQ(r.status, 0);
        }
    }
    // And once its temporary is there, so that a build is killed before it finished however fast
    // the machine runs it: the previous store stays.
    pid_t pid = 0;
    for (int attempt = 0; attempt < 5 && pid == 0; ++attempt) {
        pid = signal_while_writing(store, SIGKILL);
        if (pid == 0) { // it finished first: the small store again
            ASSERT_EQ(tinlod::test::run_cli("build " + tinlod::test::asset("dem_squared.tif") +
                                            " -o " + store)
                          .status,
                      0);
        }
    }
    ASSERT_GT(pid, 0) << "no build was caught writing";
    int status = 0;
    waitpid(pid, &status, 0);
    TileStore opened(store);
    EXPECT_EQ(opened.frame().width, 129);
    EXPECT_NO_THROW(opened.heightfield());
    ++previous;
    std::printf("killed builds: %d left the previous store, %d had finished\n", previous, replaced);
}

// Ctrl-C at any moment: the build stops (or has finished), and the folder holds the previous store
// or the new one and nothing else: no temporary is left behind, unlike after SIGKILL.
TEST(StoreKill, InterruptedBuildLeavesNoTemporary) {
    namespace fs = std::filesystem;
    const std::string dir = tinlod::test::temp_dir();
    const std::string store = dir + "/terrain.tlq";
    ASSERT_EQ(
        tinlod::test::run_cli("build " + tinlod::test::asset("dem_squared.tif") + " -o " + store)
            .status,
        0);
    // Waits for build `pid`, interrupted, and checks what it left: whether it stopped midway.
    const auto stopped_midway = [&](pid_t pid) {
        int status = 0;
        waitpid(pid, &status, 0);
        // Stopped while it wrote or built: exit status 130 and its message. Stopped before it
        // began (no temporary yet) the signal's default action ends it.
        const bool midway = WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGINT;
        if (midway) {
            std::ifstream err(dir + "/err");
            std::string line;
            std::getline(err, line);
            EXPECT_NE(line.find("tinlod: interrupted"), std::string::npos) << line;
        } else {
            EXPECT_TRUE((WIFEXITED(status) && WEXITSTATUS(status) == 0) ||
                        (WIFSIGNALED(status) && WTERMSIG(status) == SIGINT))
                << status;
        }
        std::vector<std::string> names;
        for (const auto &e : fs::directory_iterator(dir))
            if (e.path().filename() != "err")
                names.push_back(e.path().filename().string());
        EXPECT_EQ(names, std::vector<std::string>{"terrain.tlq"});
        TileStore opened(store);
        EXPECT_NO_THROW(opened.heightfield());
        return midway;
    };
    for (int delay_ms : {0, 20, 60, 100, 150, 200, 300, 500}) {
        SCOPED_TRACE(delay_ms);
        const pid_t pid = tinlod::test::start_cli(
            {"build", tinlod::test::asset("N42E001.hgt"), "-o", store}, dir + "/err");
        ASSERT_GT(pid, 0);
        usleep(useconds_t(delay_ms) * 1000);
        kill(pid, SIGINT);
        stopped_midway(pid);
    }
    // And once its temporary is there, so that a build is interrupted midway however fast the
    // machine runs it (the delays above may all fall before or after, as under the sanitizers
    // beside another test).
    bool caught = false;
    for (int attempt = 0; attempt < 5 && !caught; ++attempt)
        if (const pid_t pid = signal_while_writing(store, SIGINT, dir + "/err"))
            caught = stopped_midway(pid);
    EXPECT_TRUE(caught) << "no build was stopped midway: the test proved nothing";
}

// A build killed while it writes leaves its temporary (SIGKILL cannot be caught); the next write
// into that folder removes it, but not the temporary of a writer that still runs (here stopped
// with SIGSTOP midway), until that one has been killed too.
TEST(StoreKill, TheNextWriteRemovesAKilledWritersTemporary) {
    const std::string dir = tinlod::test::temp_dir();
    const std::string store = dir + "/terrain.tlq", other = dir + "/other.tlq";
    const std::string prefix = ".terrain.tlq.tinlod-";
    const auto build_other = [&] {
        ASSERT_EQ(tinlod::test::run_cli("build " + tinlod::test::asset("dem_squared.tif") + " -o " +
                                        other)
                      .status,
                  0);
    };
    pid_t pid = 0;
    for (int attempt = 0; attempt < 5 && pid == 0; ++attempt)
        pid = signal_while_writing(store, SIGSTOP);
    ASSERT_GT(pid, 0) << "no build was caught writing";
    build_other();
    EXPECT_EQ(temporaries(dir, prefix).size(), 1u) << "a running writer's temporary was removed";
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_EQ(temporaries(dir, prefix).size(), 1u) << "SIGKILL left no temporary";
    build_other();
    EXPECT_TRUE(temporaries(dir, prefix).empty()) << "the killed writer's temporary is still there";
    EXPECT_TRUE(temporaries(dir, ".other.tlq.").empty());
}
