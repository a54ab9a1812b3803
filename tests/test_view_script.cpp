// tinlod-view's scripted mode under Xvfb: a camera path over a real DEM gives a screenshot whose
// terrain covers the share of the frame the camera geometry says it must (and no more), with varied
// shading, and per-frame stats whose node count follows the observer. Skipped, with the reason,
// where xvfb-run is missing or the viewer finds no display / no OpenGL.
#include "assets.hpp"

#include "tinlod/camera_path.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/render.hpp"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <sys/wait.h>
#include <vector>

namespace fs = std::filesystem;
using namespace tinlod;

namespace {

struct ViewRun {
    int status = 0;
    std::string err;
};

std::string slurp(const fs::path &p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs the viewer with `args` (each passed as one word); under xvfb-run when `display` is true.
// In sanitizer builds (`make test SANITIZE=...`) the windowed viewer's leak check is off: Mesa's
// driver under Xvfb leaks 112 bytes that LeakSanitizer reports from the driver once it is
// unloaded, with no name a suppression could match. ASan and UBSan still check it, and the viewer's
// core is leak-checked in process by the ViewWorker tests.
ViewRun run_view(const std::vector<std::string> &args, bool display) {
    const fs::path dir = test::temp_dir();
    std::ostringstream cmd;
    if (display)
        cmd << "LSAN_OPTIONS=\"${LSAN_OPTIONS}:detect_leaks=0\" ";
    cmd << (display ? "timeout 300 xvfb-run -a -s '-screen 0 1280x720x24' " : "timeout 300 ")
        << '\'' << TINLOD_VIEW << '\'';
    for (const std::string &a : args)
        cmd << " '" << a << '\'';
    cmd << " >/dev/null 2>'" << (dir / "err").string() << '\'';
    const int raw = std::system(cmd.str().c_str());
    ViewRun r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.err = slurp(dir / "err");
    return r;
}

bool have_xvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

// The viewer names the display or OpenGL when it cannot get a window or a context.
bool no_gl(const ViewRun &r) {
    return r.status != 0 && (r.err.find("display:") != std::string::npos ||
                             r.err.find("OpenGL") != std::string::npos);
}

struct Row {
    double t = 0.0;
    std::int64_t nodes = 0, triangles = 0;
};

std::vector<Row> read_stats(const std::string &file) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line.rfind("frame,t,nodes,triangles", 0), 0u) << line;
    std::vector<Row> rows;
    while (std::getline(in, line)) {
        std::stringstream s(line);
        std::string cell[4];
        for (auto &c : cell)
            std::getline(s, c, ',');
        rows.push_back({std::stod(cell[1]), std::stoll(cell[2]), std::stoll(cell[3])});
    }
    return rows;
}

// Which pixels' rays must / may meet the terrain of `hf`: a ray from an eye above the surface that
// reaches z_min inside the grid's footprint must cross the surface first; a ray that never gets
// down to z_max over the footprint cannot meet it. Row 0 at the top, as in Image.
struct Coverage {
    std::vector<std::uint8_t> must, may;
};

Coverage terrain_coverage(const View &view, const Heightfield &hf) {
    const double x1 = (hf.width - 1) * hf.dx, y1 = (hf.height - 1) * hf.dy;
    const double zmin = hf.min_z(), zmax = hf.max_z();
    const glm::dmat4 inv = glm::inverse(view.projection_matrix(1.0, 1e7) * view.view_matrix());
    Coverage cover;
    cover.must.assign(std::size_t(view.viewport_w) * view.viewport_h, 0);
    cover.may = cover.must;
    for (int py = 0; py < view.viewport_h; ++py)
        for (int px = 0; px < view.viewport_w; ++px) {
            const std::size_t i = std::size_t(py) * view.viewport_w + px;
            const glm::dvec4 ndc(2.0 * (px + 0.5) / view.viewport_w - 1.0,
                                 1.0 - 2.0 * (py + 0.5) / view.viewport_h, 1.0, 1.0);
            const glm::dvec4 far = inv * ndc;
            const glm::dvec3 d = glm::normalize(glm::dvec3(far) / far.w - view.eye);
            // The ray's parameter range over the footprint (slabs in x and y).
            double t0 = 0.0, t1 = 1e18;
            const double lo[2] = {0.0, 0.0}, hi[2] = {x1, y1};
            bool crosses = true;
            for (int a = 0; a < 2; ++a) {
                if (d[a] == 0.0) {
                    crosses = crosses && view.eye[a] >= lo[a] && view.eye[a] <= hi[a];
                    continue;
                }
                double ta = (lo[a] - view.eye[a]) / d[a], tb = (hi[a] - view.eye[a]) / d[a];
                if (ta > tb)
                    std::swap(ta, tb);
                t0 = std::max(t0, ta);
                t1 = std::min(t1, tb);
            }
            if (!crosses || t0 > t1)
                continue;
            cover.may[i] = view.eye.z + (d.z < 0.0 ? t1 : t0) * d.z <= zmax;
            if (d.z < 0.0) {
                const glm::dvec3 p = view.eye + (zmin - view.eye.z) / d.z * d;
                cover.must[i] = p.x >= 0.0 && p.x <= x1 && p.y >= 0.0 && p.y <= y1;
            }
        }
    return cover;
}

// Checks the screenshot of the last view of `path` over `hf`.
void check_screenshot(const std::string &png, const View &last, const Heightfield &hf) {
    const Image image = read_image(png);
    ASSERT_EQ(image.width, last.viewport_w);
    ASSERT_EQ(image.height, last.viewport_h);
    // The eye is over the grid and above its surface there (the coverage argument needs it).
    const int c = int(std::lround(last.eye.x / hf.dx)), r = int(std::lround(last.eye.y / hf.dy));
    ASSERT_TRUE(c >= 0 && r >= 0 && c < hf.width && r < hf.height);
    ASSERT_GT(last.eye.z, hf.at(c, r));

    const Coverage cover = terrain_coverage(last, hf);
    const glm::vec3 sky = RenderOptions{}.sky * 255.0f;
    std::int64_t terrain = 0, must = 0, must_missed = 0, cannot = 0, cannot_drawn = 0;
    double sum = 0.0, sum2 = 0.0;
    std::set<std::uint32_t> colours;
    for (std::size_t i = 0; i < cover.must.size(); ++i) {
        const std::uint8_t *p = &image.rgba[4 * i];
        const bool is_sky = std::abs(p[0] - sky.r) <= 2.0f && std::abs(p[1] - sky.g) <= 2.0f &&
                            std::abs(p[2] - sky.b) <= 2.0f;
        must += cover.must[i];
        must_missed += cover.must[i] && is_sky;
        cannot += !cover.may[i];
        cannot_drawn += !cover.may[i] && !is_sky;
        if (is_sky)
            continue;
        ++terrain;
        const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        sum += y;
        sum2 += y * y;
        colours.insert(std::uint32_t(p[0]) << 16 | std::uint32_t(p[1]) << 8 | p[2]);
    }
    const double n = double(cover.must.size());
    ASSERT_GT(must / n, 0.2) << "the path's last view should look at the terrain";
    // Pixel-centre rays against rasterised coverage: allow the pixels of one silhouette row.
    const double slack = 2.0 * image.width;
    EXPECT_LE(double(must_missed), slack)
        << must_missed << " of " << must << " pixels that must show terrain show sky";
    EXPECT_LE(double(cannot_drawn), slack)
        << cannot_drawn << " of " << cannot << " pixels that cannot show terrain do";
    const double mean = sum / double(terrain);
    const double sd = std::sqrt(std::max(0.0, sum2 / double(terrain) - mean * mean));
    EXPECT_GT(sd, 8.0) << "hill shading should vary over real terrain";
    EXPECT_GT(colours.size(), 200u);
}

void check_stats(const std::vector<Row> &rows, int frames, double duration, std::int64_t samples) {
    ASSERT_EQ(rows.size(), std::size_t(frames));
    EXPECT_NEAR(rows.back().t - rows.front().t, duration, 1e-6);
    std::set<std::int64_t> counts;
    for (const Row &row : rows) {
        EXPECT_GT(row.nodes, 3);
        EXPECT_LE(row.nodes, samples);
        // A triangulated disc: T = 2N - B - 2 < 2N.
        EXPECT_LT(row.triangles, 2 * row.nodes);
        counts.insert(row.nodes);
    }
    EXPECT_GE(counts.size(), 3u) << "the level of detail should change along the path";
    // The descent ends closer to the terrain than it starts: more detail.
    EXPECT_GT(rows.back().nodes, rows.front().nodes);
}

// A path of our own over `hf`: from far above the south edge down to just over the hilltops,
// looking north past the far edge, so the last frame shows both terrain and sky.
CameraPath approach_path(const Heightfield &hf) {
    const double w = (hf.width - 1) * hf.dx, h = (hf.height - 1) * hf.dy;
    const glm::dvec3 at(0.5 * w, 1.2 * h, hf.min_z());
    CameraPath camera;
    for (int i = 0; i <= 4; ++i) {
        const double f = 1.0 - i / 4.0; // 1 .. 0
        const glm::dvec3 eye(0.5 * w, 0.1 * h, hf.max_z() + 0.05 * w + 3.0 * w * f);
        camera.keys.push_back({double(i), eye, at});
    }
    return camera;
}

// Plays approach_path(hf) over `dem` in the viewer (480x320, shaded, plus `extra` options) and
// checks its last screenshot against hf's geometry and its stats against the path's 5 frames.
void play_and_check_approach(const std::string &dem, const Heightfield &hf,
                             const std::vector<std::string> &extra) {
    const CameraPath camera = approach_path(hf);
    const std::string dir = test::temp_dir();
    write_camera_path(camera, dir + "/path.csv");
    std::vector<std::string> args = {
        dem,       "--script",         dir + "/path.csv", "--screenshot", dir + "/shot.png",
        "--stats", dir + "/stats.csv", "--size",          "480x320",      "--color",
        "shade"};
    args.insert(args.end(), extra.begin(), extra.end());
    const ViewRun run = run_view(args, true);
    if (no_gl(run))
        GTEST_SKIP() << "no display or OpenGL under Xvfb: " << run.err;
    ASSERT_EQ(run.status, 0) << run.err;
    View base;
    base.viewport_w = 480;
    base.viewport_h = 320;
    check_screenshot(dir + "/shot.png", camera.at_time(camera.keys.back().t, base), hf);
    check_stats(read_stats(dir + "/stats.csv"), 5, camera.duration(), hf.size());
}

} // namespace

TEST(ViewScript, DescentOverN42E001) {
    if (!have_xvfb())
        GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
    const std::string dem = test::asset("N42E001.hgt");
    const std::string path = test::asset("paths/n42_descent.csv");
    const std::string dir = test::temp_dir();
    const int frames = 8;
    const ViewRun run =
        run_view({dem, "--script", path, "--screenshot", dir + "/shot.png", "--stats",
                  dir + "/stats.csv", "--frames", std::to_string(frames), "--size", "640x360"},
                 true);
    if (no_gl(run))
        GTEST_SKIP() << "no display or OpenGL under Xvfb: " << run.err;
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_TRUE(run.err.empty()) << run.err;

    const Heightfield hf = load_heightfield(dem);
    const CameraPath camera = read_camera_path(path);
    View base;
    base.viewport_w = 640;
    base.viewport_h = 360;
    check_screenshot(dir + "/shot.png", camera.at_time(camera.keys.back().t, base), hf);
    check_stats(read_stats(dir + "/stats.csv"), frames, camera.duration(), hf.size());
}

TEST(ViewScript, ApproachOverDemSquared) {
    if (!have_xvfb())
        GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
    const std::string dem = test::asset("dem_squared.tif");
    play_and_check_approach(dem, load_heightfield(dem), {"--wire"});
}

TEST(ViewScript, BadInputsFailWithOneLineNamingTheFile) {
    const std::string dir = test::temp_dir();
    const std::string shot = dir + "/shot.png";
    // Files are checked before any window opens: no display is needed for these.
    const ViewRun missing = run_view(
        {dir + "/nope.hgt", "--script", test::asset("paths/n42_descent.csv"), "--screenshot", shot},
        false);
    EXPECT_NE(missing.status, 0);
    EXPECT_NE(missing.err.find("nope.hgt"), std::string::npos) << missing.err;
    EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;

    {
        std::ofstream bad(dir + "/bad.csv");
        bad << "t,eye_x,eye_y,eye_z,at_x,at_y,at_z\n0,1,2,3,1,2,3\n";
    }
    const ViewRun path = run_view(
        {test::asset("dem_squared.tif"), "--script", dir + "/bad.csv", "--screenshot", shot},
        false);
    EXPECT_NE(path.status, 0);
    EXPECT_NE(path.err.find("bad.csv"), std::string::npos) << path.err;
    EXPECT_EQ(std::count(path.err.begin(), path.err.end(), '\n'), 1) << path.err;

    const ViewRun no_shot = run_view(
        {test::asset("dem_squared.tif"), "--script", test::asset("paths/n42_descent.csv")}, false);
    EXPECT_NE(no_shot.status, 0);
    EXPECT_NE(no_shot.err.find("--screenshot"), std::string::npos) << no_shot.err;
    EXPECT_FALSE(fs::exists(shot));
}

// The viewer reads rasters as the command line does: a 16-bit PNG at the cell size and height
// scale given, a Terrain-RGB tile decoded. Its screenshot covers the frame the terrain read with
// the same options must cover (at 1 m cells, or undecoded, the terrain would be elsewhere
// entirely).
TEST(ViewScript, RasterOptionsAsTheCommandLine) {
    if (!have_xvfb())
        GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
    struct Case {
        std::string file;
        std::vector<std::string> args;
        LoadOptions load;
    };
    LoadOptions crater, fuji;
    crater.cell = 10.0;
    crater.zscale = 1.5;
    fuji.cell = 30.0;
    fuji.terrain_rgb = true;
    for (const Case &c : {Case{"crater_u16.png", {"--cell", "10", "--zscale", "1.5"}, crater},
                          Case{"fuji.png", {"--terrain-rgb", "--cell", "30"}, fuji}}) {
        SCOPED_TRACE(c.file);
        const std::string dem = test::asset(c.file);
        play_and_check_approach(dem, load_heightfield(dem, c.load), c.args);
    }
}

TEST(ViewScript, BadRasterOptionIsNamed) {
    // Checked as the command line's, before any window opens: no display is needed.
    const std::string dir = test::temp_dir();
    const ViewRun run =
        run_view({test::asset("crater_u16.png"), "--cell", "0", "--script",
                  test::asset("paths/n42_descent.csv"), "--screenshot", dir + "/shot.png"},
                 false);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err.rfind("tinlod-view: --cell", 0), 0u) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(dir + "/shot.png"));
}
