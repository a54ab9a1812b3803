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
    EXPECT_GT(previous, 0) << "no build was killed before it finished: the test proved nothing";
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
    int stopped = 0;
    for (int delay_ms : {0, 20, 60, 100, 150, 200, 300, 500}) {
        SCOPED_TRACE(delay_ms);
        const pid_t pid = tinlod::test::start_cli(
            {"build", tinlod::test::asset("N42E001.hgt"), "-o", store}, dir + "/err");
        ASSERT_GT(pid, 0);
        usleep(useconds_t(delay_ms) * 1000);
        kill(pid, SIGINT);
        int status = 0;
        waitpid(pid, &status, 0);
        // Stopped while it wrote or built: exit status 130 and its message. Stopped before it
        // began (no temporary yet) the signal's default action ends it.
        if (WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGINT) {
            ++stopped;
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
    }
    EXPECT_GT(stopped, 0) << "no build was stopped midway: the test proved nothing";
}
