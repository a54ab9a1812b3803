// Outputs never destroy what their paths name: a symbolic link is followed and stays, a character
// device or FIFO is written to directly (or refused, for a store), `-` is the standard output, two
// outputs of one command may not name the same file, a file-size limit is one error line, and the
// temporaries of killed writers are removed at start-up.
#include "assets.hpp"

#include "tinlod/render.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

using tinlod::test::asset;
using tinlod::test::run_cli;
using tinlod::test::temp_dir;

namespace fs = std::filesystem;

static const std::string k_dem = "'" + asset("dem_squared.tif") + "'"; // 129 x 129 samples

static std::string read_text(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// The names in `dir` (hidden ones too).
static std::vector<std::string> names_in(const std::string &dir) {
    std::vector<std::string> names;
    for (const auto &e : fs::directory_iterator(dir))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// A private character device with the numbers of /dev/null (1, 3) or /dev/full (1, 7).
static std::string make_device(const std::string &path, unsigned minor) {
    EXPECT_EQ(::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, minor)), 0) << path;
    return path;
}

static bool is_device(const std::string &path, unsigned minor) {
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode) &&
           st.st_rdev == makedev(1, minor);
}

TEST(Outputs, CharacterDeviceIsWrittenToNotReplaced) {
    if (::geteuid() != 0)
        GTEST_SKIP() << "mknod of a character device needs root";
    const std::string dir = temp_dir();
    const std::string null = make_device(dir + "/null.ply", 3);
    const std::string stats = make_device(dir + "/stats", 3);
    auto r = run_cli("retrieve --full " + k_dem + " -o " + null + " --stats " + stats);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(is_device(null, 3)) << "the mesh output replaced the device";
    EXPECT_TRUE(is_device(stats, 3)) << "the stats output replaced the device";

    // A device that refuses the bytes (as /dev/full): one error line, and the device stays.
    const std::string full = make_device(dir + "/full", 7);
    r = run_cli("retrieve --full " + k_dem + " -o " + dir + "/grid.ply --stats " + full);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(full + ": cannot write: No space left on device"), std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(is_device(full, 7));

    // A store is written with seeks: refused before the work, the device untouched.
    r = run_cli("build " + k_dem + " -o " + full);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(full + ": a store is written with seeks"), std::string::npos) << r.err;
    EXPECT_TRUE(is_device(full, 7));
    EXPECT_EQ(names_in(dir), (std::vector<std::string>{"full", "grid.ply", "null.ply", "stats"}))
        << "a temporary left behind";
}

// Reads everything written into the FIFO `path` while `run` runs (the FIFO is held open for
// reading and writing, so that neither side waits for the other).
template <class Run> static std::string read_fifo_while(const std::string &path, Run run) {
    const int fd = ::open(path.c_str(), O_RDWR | O_NONBLOCK);
    EXPECT_GE(fd, 0);
    std::string bytes;
    std::atomic<bool> done{false};
    std::thread reader([&] {
        char buf[65536];
        for (;;) {
            pollfd p{fd, POLLIN, 0};
            const bool ready = ::poll(&p, 1, 20) > 0;
            const ssize_t n = ready ? ::read(fd, buf, sizeof buf) : 0;
            if (n > 0)
                bytes.append(buf, std::size_t(n));
            else if (done)
                return;
        }
    });
    run();
    done = true;
    reader.join();
    ::close(fd);
    return bytes;
}

TEST(Outputs, FifoIsStreamedInto) {
    const std::string dir = temp_dir();
    const std::string fifo = dir + "/stats.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    int status = -1;
    const std::string text = read_fifo_while(fifo, [&] {
        const auto r =
            run_cli("retrieve --full " + k_dem + " -o " + dir + "/grid.ply --stats " + fifo);
        status = r.status;
        EXPECT_EQ(r.status, 0) << r.err;
    });
    struct stat st {};
    ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
    ASSERT_EQ(status, 0);
    const auto stats = nlohmann::json::parse(text);
    EXPECT_EQ(stats["output"]["nodes"], 129 * 129);
    EXPECT_EQ(names_in(dir), (std::vector<std::string>{"grid.ply", "stats.json"}));
}

// A symbolic link is followed: the file it names is replaced in its own folder, and it stays a
// link; a dangling one gets the file it names created.
TEST(Outputs, SymlinkIsFollowedAndStays) {
    const std::string dir = temp_dir();
    fs::create_directory(dir + "/real");
    std::ofstream(dir + "/real/old.json") << "old\n";
    fs::create_symlink("real/old.json", dir + "/stats.json");
    fs::create_symlink("real/new.ply", dir + "/grid.ply"); // dangling
    const auto r = run_cli("retrieve --full " + k_dem + " -o " + dir + "/grid.ply --stats " + dir +
                           "/stats.json");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char *link : {"/stats.json", "/grid.ply"}) {
        SCOPED_TRACE(link);
        EXPECT_TRUE(fs::is_symlink(dir + link)) << "the link was replaced";
    }
    EXPECT_EQ(fs::read_symlink(dir + "/stats.json"), "real/old.json");
    EXPECT_EQ(fs::read_symlink(dir + "/grid.ply"), "real/new.ply");
    const auto stats = nlohmann::json::parse(read_text(dir + "/real/old.json"));
    EXPECT_EQ(stats["output"]["nodes"], 129 * 129);
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir + "/real/new.ply")));
    EXPECT_GT(fs::file_size(dir + "/real/new.ply"), 129u * 129u * 12u);
    EXPECT_EQ(names_in(dir), (std::vector<std::string>{"grid.ply", "real", "stats.json"}));
    EXPECT_EQ(names_in(dir + "/real"), (std::vector<std::string>{"new.ply", "old.json"}));
}

TEST(Outputs, SymlinkLoopIsRefusedAndStays) {
    const std::string dir = temp_dir();
    fs::create_symlink("b.json", dir + "/a.json");
    fs::create_symlink("a.json", dir + "/b.json");
    const auto r =
        run_cli("retrieve --full " + k_dem + " -o " + dir + "/grid.ply --stats " + dir + "/a.json");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(dir + "/a.json: too many levels of symbolic links"), std::string::npos)
        << r.err;
    EXPECT_TRUE(fs::is_symlink(dir + "/a.json"));
    EXPECT_EQ(names_in(dir), (std::vector<std::string>{"a.json", "b.json"})) << "work was done";
}

// `--stats -` writes the JSON to the standard output, and the command's summary goes to stderr.
TEST(Outputs, DashIsTheStandardOutput) {
    const std::string dir = temp_dir();
    const auto r = run_cli("retrieve --full " + k_dem + " -o " + dir + "/grid.ply --stats -");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(r.out); // throws on anything but one JSON document
    EXPECT_EQ(stats["output"]["nodes"], 129 * 129);
    EXPECT_NE(r.err.find("grid.ply"), std::string::npos) << "no summary on stderr: " << r.err;
    EXPECT_EQ(names_in(dir), (std::vector<std::string>{"grid.ply"})) << "a file named '-'";
}

// Two outputs naming one file, in any spelling: a usage error before any work.
TEST(Outputs, TwoOutputsNamingOneFileAreAUsageError) {
    const std::string dir = temp_dir();
    fs::create_directory(dir + "/sub");
    fs::create_symlink("sub", dir + "/via");
    fs::create_symlink("sub/t.ply", dir + "/link.ply");
    std::ofstream(dir + "/sub/t.ply") << "previous\n";
    const std::vector<std::pair<std::string, std::string>> pairs = {
        {dir + "/sub/t.ply", dir + "/sub/t.ply"},
        {dir + "/sub/t.ply", dir + "/sub/./t.ply"},
        {dir + "/sub/t.ply", dir + "/via/t.ply"},
        {dir + "/sub/t.ply", dir + "/link.ply"},
        {dir + "/sub/new.ply", dir + "/via/../sub/new.ply"}, // not there yet
        {"new-output.ply", "./new-output.ply"},              // relative, not there yet
    };
    for (const auto &[output, stats] : pairs) {
        SCOPED_TRACE(output + " and " + stats);
        const auto r = run_cli("retrieve '" + asset("no-such-dem.tif") + "' --full -o " + output +
                               " --stats " + stats);
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_NE(r.err.find("--stats: names the same file as --output"), std::string::npos)
            << r.err;
        EXPECT_EQ(r.err.find("no-such-dem"), std::string::npos) << "the input was read first";
        EXPECT_EQ(read_text(dir + "/sub/t.ply"), "previous\n");
    }
    const auto r = run_cli("render " + k_dem + " --eye 1,1,900 --at 500,500,0 -o " + dir +
                           "/f.exr --depth " + dir + "/./f.exr");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("--depth: names the same file as --output"), std::string::npos) << r.err;
    EXPECT_EQ(names_in(dir), (std::vector<std::string>{"link.ply", "sub", "via"}));
    EXPECT_EQ(names_in(dir + "/sub"), (std::vector<std::string>{"t.ply"}));
}

// A file-size limit: one error line, exit 1, and neither the file nor its temporary left (the
// program's own handling: run_cli leaves SIGXFSZ at its default, which kills).
TEST(Outputs, FileSizeLimitIsOneErrorLineAndNoTemporary) {
    const std::string dir = temp_dir();
    const auto r =
        run_cli("build " + k_dem + " -o " + dir + "/t.tlq --stats " + dir + "/s.json", 16u << 10);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find(dir + "/t.tlq: cannot write: File too large"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(names_in(dir).empty()) << names_in(dir).front();
}

// A writer killed by SIGKILL leaves its temporary; the next command that writes into that folder
// removes it at start-up, even when that command then fails on its input.
TEST(Outputs, KilledWritersTemporariesAreRemovedAtStartUp) {
    const std::string dir = temp_dir();
    const auto hidden = [&] {
        std::vector<std::string> names = names_in(dir);
        names.erase(std::remove_if(names.begin(), names.end(),
                                   [](const std::string &n) { return n[0] != '.'; }),
                    names.end());
        return names;
    };
    // A build of the large tile, killed once its temporary is there.
    bool caught = false;
    for (int attempt = 0; attempt < 5 && !caught; ++attempt) {
        const pid_t pid =
            tinlod::test::start_cli({"build", asset("N42E001.hgt"), "-o", dir + "/t.tlq"});
        for (int i = 0; i < 20000 && !caught; ++i) {
            caught = !hidden().empty();
            if (!caught)
                ::usleep(500);
        }
        ::kill(pid, SIGKILL);
        int status = 0;
        ::waitpid(pid, &status, 0);
        caught = !hidden().empty();
    }
    ASSERT_TRUE(caught) << "no build was caught writing";
    const auto r =
        run_cli("retrieve '" + asset("no-such-dem.tif") + "' --full -o " + dir + "/grid.ply");
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(hidden().empty()) << hidden().front();
}

// fly's output folders are created when missing (both of them), and removed again when the
// flight fails.
TEST(Outputs, FlyCreatesItsFoldersAndRemovesThemOnFailure) {
    const std::string dir = temp_dir();
    std::ofstream(dir + "/path.csv") << "t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n"
                                        "0,10,10,300,64,64,0\n"
                                        "1,30,30,250,64,64,0\n";
    const std::string fly = "fly " + k_dem + " --path " + dir + "/path.csv --fps 1";
    const bool drawn = tinlod::render_available();
    const std::string frames = dir + "/out/frames", meshes = dir + "/out/meshes";
    const auto r = run_cli(fly + " --meshes " + meshes + (drawn ? " --frames " + frames : ""));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(names_in(meshes), (std::vector<std::string>{"frame_00000.ply", "frame_00001.ply"}));
    if (drawn) {
        EXPECT_EQ(names_in(frames),
                  (std::vector<std::string>{"frame_00000.png", "frame_00001.png"}));
    }

    // A flight whose first TIN cannot be written (past a file-size limit) leaves no folder.
    const auto failed = run_cli(fly + " --meshes " + dir + "/new/meshes", 1024);
    EXPECT_EQ(failed.status, 1) << failed.err;
    EXPECT_NE(failed.err.find("File too large"), std::string::npos) << failed.err;
    EXPECT_FALSE(fs::exists(dir + "/new"));
}
