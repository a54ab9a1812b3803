// The viewer's input handling without a window (apps/view/camera_control.hpp): fly and orbit
// motion from key and mouse events, terrain following, camera path record -> CSV -> replay; and
// the LOD worker's latest-request-wins protocol (apps/view/lod_worker.hpp).
#include "assets.hpp"
#include "camera_control.hpp"
#include "lod_worker.hpp"

#include "tinlod/camera_path.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <mutex>

using namespace tinlod;
using namespace tinlod::viewer;

namespace {

void expect_near(const glm::dvec3 &a, const glm::dvec3 &b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

CameraControl camera(const glm::dvec3 &eye, const glm::dvec3 &at) {
    CameraControl c;
    c.look_at(eye, at);
    return c;
}

} // namespace

TEST(ViewInput, ForwardKeyMovesAlongTheViewDirectionBySpeedTimesDt) {
    const glm::dvec3 eye(100.0, 200.0, 300.0), at(140.0, 230.0, 250.0);
    CameraControl c = camera(eye, at);
    c.set_speed(12.5);
    MoveKeys keys;
    keys.forward = true;
    c.update(keys, 0.08);
    const glm::dvec3 step = c.eye() - eye;
    EXPECT_NEAR(glm::length(step), 12.5 * 0.08, 1e-9);
    expect_near(glm::normalize(step), glm::normalize(at - eye), 1e-9);
    // Moving does not turn the head.
    expect_near(c.direction(), glm::normalize(at - eye), 1e-12);

    keys = MoveKeys{};
    keys.back = true;
    c.update(keys, 0.08);
    expect_near(c.eye(), eye, 1e-9);
}

TEST(ViewInput, StrafeIsHorizontalAndUpIsVertical) {
    const glm::dvec3 eye(0.0, 0.0, 50.0);
    CameraControl c = camera(eye, {10.0, 0.0, 40.0}); // looking east and down
    c.set_speed(2.0);
    MoveKeys keys;
    keys.right = true;
    c.update(keys, 1.0);
    // Right of east, seen with z up, is south; the height stays.
    expect_near(c.eye(), eye + glm::dvec3(0.0, -2.0, 0.0), 1e-12);
    keys = MoveKeys{};
    keys.up = true;
    c.update(keys, 0.5);
    expect_near(c.eye(), eye + glm::dvec3(0.0, -2.0, 1.0), 1e-12);
}

TEST(ViewInput, MouseLookTurnsYawAndPitchAndClampsPitch) {
    ControlOptions options;
    CameraControl c(options);
    c.look_at({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0});
    EXPECT_NEAR(c.yaw(), 0.0, 1e-12);
    EXPECT_NEAR(c.pitch(), 0.0, 1e-12);
    c.drag(-100.0, 0.0); // mouse left: turn left (counter-clockwise seen from above)
    EXPECT_NEAR(c.yaw(), 100.0 * options.look_rad_per_px, 1e-12);
    EXPECT_NEAR(c.pitch(), 0.0, 1e-12);
    c.drag(0.0, -50.0); // mouse up: look up
    EXPECT_NEAR(c.pitch(), 50.0 * options.look_rad_per_px, 1e-12);
    // The eye does not move in fly mode.
    expect_near(c.eye(), glm::dvec3(0.0), 0.0);

    c.drag(0.0, -1e6);
    EXPECT_NEAR(c.pitch(), options.max_pitch_rad, 1e-12);
    c.drag(0.0, 1e6);
    EXPECT_NEAR(c.pitch(), -options.max_pitch_rad, 1e-12);
    // The axis never turns vertical, so the view matrix stays defined.
    EXPECT_LT(std::abs(c.direction().z), 1.0 - 1e-6);
    const View v = c.view(View{});
    EXPECT_NO_THROW(validate(v));

    // A camera placed looking straight down is clamped too.
    c.look_at({0.0, 0.0, 10.0}, {0.0, 0.0, 0.0});
    EXPECT_NEAR(c.pitch(), -options.max_pitch_rad, 1e-12);
}

TEST(ViewInput, OrbitKeepsTheDistanceToTheFocalPointAndLooksAtIt) {
    const glm::dvec3 pivot(500.0, 400.0, 80.0);
    CameraControl c = camera({300.0, 100.0, 600.0}, {310.0, 120.0, 580.0});
    c.set_mode(NavMode::orbit, pivot);
    ASSERT_EQ(c.mode(), NavMode::orbit);
    const double d0 = glm::length(c.eye() - pivot);
    expect_near(c.direction(), glm::normalize(pivot - c.eye()), 1e-9);

    c.drag(140.0, -35.0);
    MoveKeys keys;
    keys.left = true;
    keys.up = true;
    c.update(keys, 0.3);
    EXPECT_NEAR(glm::length(c.eye() - pivot), d0, 1e-9 * d0);
    expect_near(c.direction(), glm::normalize(pivot - c.eye()), 1e-9);
    // The view's look-at point is the pivot.
    expect_near(c.view(View{}).at, pivot, 1e-9 * d0);

    // W moves toward the pivot, the wheel too; both keep looking at it.
    keys = MoveKeys{};
    keys.forward = true;
    c.update(keys, 0.5);
    const double d1 = glm::length(c.eye() - pivot);
    EXPECT_NEAR(d1, d0 * std::exp(-0.5), 1e-9 * d0);
    c.scroll(2.0);
    EXPECT_NEAR(glm::length(c.eye() - pivot),
                d1 / (ControlOptions{}.wheel_factor * ControlOptions{}.wheel_factor), 1e-9 * d0);
    expect_near(c.direction(), glm::normalize(pivot - c.eye()), 1e-9);
}

TEST(ViewInput, WheelScalesFlySpeedAndResetRestoresHome) {
    const glm::dvec3 eye(1.0, 2.0, 3.0);
    CameraControl c = camera(eye, {4.0, 6.0, 3.0});
    c.set_speed(10.0);
    c.set_home();
    c.scroll(3.0);
    EXPECT_NEAR(c.speed(), 10.0 * std::pow(ControlOptions{}.wheel_factor, 3.0), 1e-9);
    c.scroll(-3.0);
    EXPECT_NEAR(c.speed(), 10.0, 1e-9);

    c.drag(55.0, 20.0);
    MoveKeys keys;
    keys.forward = keys.left = true;
    c.update(keys, 1.0);
    c.set_mode(NavMode::orbit, {0.0, 0.0, 0.0});
    c.reset();
    EXPECT_EQ(c.mode(), NavMode::fly);
    expect_near(c.eye(), eye, 0.0);
    expect_near(c.view(View{}).at, glm::dvec3(4.0, 6.0, 3.0), 1e-12);
}

TEST(ViewInput, TerrainFollowingLiftsTheEyeOnlyWhenTooLow) {
    CameraControl c = camera({0.0, 0.0, 120.0}, {100.0, 0.0, 120.0});
    c.keep_above(100.0, 10.0); // 120 >= 110: stays
    EXPECT_EQ(c.eye().z, 120.0);
    c.keep_above(115.0, 10.0);
    EXPECT_EQ(c.eye().z, 125.0);
    // The heading is kept in fly mode.
    expect_near(c.direction(), glm::dvec3(1.0, 0.0, 0.0), 1e-12);
}

TEST(ViewInput, RecordedPathRoundTripsThroughTheCsv) {
    CameraControl c = camera({0.0, 0.0, 500.0}, {1000.0, 0.0, 0.0});
    c.set_speed(40.0);
    PathRecorder recorder(0.25);
    recorder.start(100.0);
    std::vector<Keyframe> expected;
    MoveKeys keys;
    keys.forward = true;
    // Frames of 0.1 s: a keyframe is due every 0.25 s of recording time.
    double now = 100.0;
    for (int frame = 0; frame <= 12; ++frame, now += 0.1) {
        const View v = c.view(View{});
        const std::size_t before = recorder.path().keys.size();
        recorder.sample(now, v);
        if (recorder.path().keys.size() > before)
            expected.push_back({now - 100.0, v.eye, v.at});
        if (frame == 6) // a still camera adds no keyframes
            keys.forward = false;
        c.update(keys, 0.1);
        c.drag(frame == 9 ? 30.0 : 0.0, 0.0);
    }
    // Kept: t = 0 and every frame at least 0.25 s after the last keyframe while moving; the still
    // camera of frames 6..9 adds one keyframe at most.
    ASSERT_GE(expected.size(), 4u);
    for (std::size_t i = 1; i < expected.size(); ++i)
        EXPECT_FALSE(expected[i].eye == expected[i - 1].eye &&
                     expected[i].at == expected[i - 1].at);
    EXPECT_EQ(expected.front().t, 0.0);
    for (std::size_t i = 1; i < expected.size(); ++i)
        EXPECT_GE(expected[i].t - expected[i - 1].t, 0.25 - 1e-9);
    const CameraPath recorded = recorder.stop(now, c.view(View{}));
    EXPECT_FALSE(recorder.recording());
    ASSERT_GE(recorded.keys.size(), expected.size());

    const std::string file = test::temp_dir() + "/path.csv";
    write_camera_path(recorded, file);
    const CameraPath read = read_camera_path(file);
    ASSERT_EQ(read.keys.size(), recorded.keys.size());
    for (std::size_t i = 0; i < read.keys.size(); ++i) {
        EXPECT_EQ(read.keys[i].t, recorded.keys[i].t);
        expect_near(read.keys[i].eye, recorded.keys[i].eye, 1e-9);
        expect_near(read.keys[i].at, recorded.keys[i].at, 1e-9);
    }
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_NEAR(read.keys[i].t, expected[i].t, 1e-9);
        expect_near(read.keys[i].eye, expected[i].eye, 1e-9);
    }
}

TEST(ViewInput, ReplayGivesTheInterpolatedCamera) {
    CameraPath path;
    path.keys = {{2.0, {0.0, 0.0, 100.0}, {10.0, 0.0, 0.0}},
                 {4.0, {20.0, 40.0, 60.0}, {30.0, 40.0, 0.0}},
                 {5.0, {20.0, 80.0, 60.0}, {20.0, 90.0, 0.0}}};
    View base;
    base.fov_deg = 45.0;
    base.viewport_w = 640;
    base.viewport_h = 480;
    PathPlayer player;
    player.start(path, 1000.0);
    ASSERT_TRUE(player.playing());
    // 1.5 s into playback = path time 3.5: three quarters of the way from key 0 to key 1.
    const auto v = player.view(1001.5, base);
    ASSERT_TRUE(v.has_value());
    expect_near(v->eye, glm::dvec3(15.0, 30.0, 70.0), 1e-12);
    expect_near(v->at, glm::dvec3(25.0, 30.0, 0.0), 1e-12);
    EXPECT_EQ(v->fov_deg, 45.0);
    EXPECT_EQ(v->viewport_w, 640);
    // Driving the camera from the replay reproduces the view.
    CameraControl c;
    c.look_at(v->eye, v->at);
    const View again = c.view(base);
    expect_near(again.eye, v->eye, 1e-12);
    expect_near(again.at, v->at, 1e-9);

    // Past the end: the last keyframe once, then playback stops.
    const auto last = player.view(1010.0, base);
    ASSERT_TRUE(last.has_value());
    expect_near(last->eye, path.keys.back().eye, 0.0);
    EXPECT_FALSE(player.playing());
    EXPECT_FALSE(player.view(1011.0, base).has_value());
}

namespace {

// Computes nothing but records which views it was asked for; the first call blocks until released.
class GateEngine final : public LodEngine {
  public:
    std::unique_ptr<LodResult> compute(const View &view, const LodSettings &) override {
        std::unique_lock lock(mutex_);
        seen_.push_back(view.eye.x);
        started_.notify_all();
        open_.wait(lock, [this] { return released_; });
        auto r = std::make_unique<LodResult>();
        r->nodes = static_cast<std::int64_t>(view.eye.x);
        return r;
    }
    void wait_started(std::size_t calls) {
        std::unique_lock lock(mutex_);
        started_.wait(lock, [&] { return seen_.size() >= calls; });
    }
    void release() {
        std::lock_guard lock(mutex_);
        released_ = true;
        open_.notify_all();
    }
    std::vector<double> seen() {
        std::lock_guard lock(mutex_);
        return seen_;
    }

  private:
    std::mutex mutex_;
    std::condition_variable started_, open_;
    bool released_ = false;
    std::vector<double> seen_;
};

View view_at_x(double x) {
    View v;
    v.eye = {x, 0.0, 10.0};
    v.at = {x, 1.0, 0.0};
    return v;
}

} // namespace

TEST(ViewWorker, LatestRequestWinsAndRequestsNeverBlock) {
    auto owned = std::make_unique<GateEngine>();
    GateEngine *engine = owned.get();
    LodWorker worker(std::move(owned));
    worker.request(view_at_x(1.0), {});
    engine->wait_started(1);
    // The engine is stuck on view 1: these return at once, and only the last one is computed.
    worker.request(view_at_x(2.0), {});
    const std::uint64_t last = worker.request(view_at_x(3.0), {});
    EXPECT_TRUE(worker.busy());
    EXPECT_EQ(worker.take(), nullptr);
    engine->release();
    const auto result = worker.wait(last);
    ASSERT_NE(result, nullptr);
    EXPECT_EQ(result->serial, last);
    EXPECT_EQ(result->nodes, 3);
    EXPECT_EQ(result->view.eye.x, 3.0);
    EXPECT_EQ(engine->seen(), (std::vector<double>{1.0, 3.0}));
}

TEST(ViewWorker, DemSceneGetsFinerAsTheEyeDescends) {
    SceneInfo info;
    auto engine = open_scene(test::asset("dem_squared.tif"), info);
    EXPECT_EQ(info.kind, "DEM");
    EXPECT_EQ(info.input_nodes, 129 * 129);
    ASSERT_LT(info.lo.z, info.hi.z);
    LodWorker worker(std::move(engine));
    const glm::dvec3 centre = 0.5 * (info.lo + info.hi);
    const double size = info.hi.x - info.lo.x;
    std::int64_t previous = 0;
    for (double height : {4.0, 1.0, 0.25}) {
        View v;
        v.viewport_w = 800;
        v.viewport_h = 600;
        v.eye = {centre.x, info.lo.y - 0.2 * size, info.hi.z + height * size};
        v.at = {centre.x, centre.y, centre.z};
        LodSettings s;
        s.cull = false;
        const auto r = worker.wait(worker.request(v, s));
        ASSERT_NE(r, nullptr) << worker.error();
        EXPECT_EQ(r->nodes, static_cast<std::int64_t>(r->mesh.n_vertices()));
        EXPECT_GT(r->nodes, previous) << "eye " << height << " sizes above the top";
        EXPECT_LE(r->bound_px, s.tol_px);
        EXPECT_TRUE(r->focal.hit);
        previous = r->nodes;
    }
}

TEST(ViewWorker, GroundUnderTheEyeIsTheDemAtFullResolution) {
    const std::string file = test::asset("dem_squared.tif");
    const Heightfield hf = load_heightfield(file);
    SceneInfo info;
    auto engine = open_scene(file, info);
    View v;
    v.eye = {0.5 * info.hi.x, -0.5 * info.hi.y, info.hi.z + info.hi.x};
    v.at = 0.5 * (info.lo + info.hi);
    LodSettings s;
    s.tol_px = 0.0; // the full grid: the TIN passes through every sample
    const auto r = engine->compute(v, s);
    ASSERT_EQ(r->nodes, hf.size());
    for (const auto &[c, row] :
         {std::pair{1, 1}, std::pair{64, 64}, std::pair{17, 101}, std::pair{127, 127}}) {
        const auto z = ground_height(*r, info, c * hf.dx, row * hf.dy);
        ASSERT_TRUE(z.has_value()) << c << ", " << row;
        EXPECT_NEAR(*z, hf.at(c, row), 1e-3) << c << ", " << row;
    }
    // Midway between samples the TIN interpolates: within the range of the cell's corners.
    const auto mid = ground_height(*r, info, 40.5 * hf.dx, 70.5 * hf.dy);
    ASSERT_TRUE(mid.has_value());
    const float corners[4] = {hf.at(40, 70), hf.at(41, 70), hf.at(40, 71), hf.at(41, 71)};
    EXPECT_GE(*mid, *std::min_element(corners, corners + 4) - 1e-3);
    EXPECT_LE(*mid, *std::max_element(corners, corners + 4) + 1e-3);
    EXPECT_FALSE(ground_height(*r, info, -10.0 * hf.dx, 5.0 * hf.dy).has_value());
}

namespace {

// 800 x 600, from south of the scene and above it, looking at its centre.
View oblique_view(const SceneInfo &info) {
    View v;
    v.viewport_w = 800;
    v.viewport_h = 600;
    v.eye = {0.5 * info.hi.x, -0.1 * info.hi.y, info.hi.z + 0.3 * info.hi.x};
    v.at = 0.5 * (info.lo + info.hi);
    return v;
}

} // namespace

TEST(ViewWorker, EraseStageThinsTheRetrievalWithinTauAtEverySample) {
    SceneInfo info;
    auto engine = open_scene(test::asset("dem_squared.tif"), info);
    const View v = oblique_view(info);
    LodSettings s;
    s.tol_px = 2.0;
    s.color = ColorBy::sp;
    const auto retrieved = engine->compute(v, s);
    s.stages = LodStages::retrieve_erase;
    const auto erased = engine->compute(v, s);
    EXPECT_LT(erased->nodes, retrieved->nodes);
    EXPECT_GT(erased->erase_ms, 0.0);
    EXPECT_LE(erased->erase_max_px, s.tol_px + 1e-9);
    // A DEM in memory: the bound holds at every sample, not only at the retrieved nodes.
    ErrorOptions eo;
    eo.model = Significance::screen(v);
    const TinError measured =
        measure_error(load_heightfield(test::asset("dem_squared.tif")), erased->mesh, eo);
    EXPECT_LE(measured.max_screen_px, s.tol_px);
    EXPECT_NEAR(measured.max_screen_px, erased->erase_max_px, 1e-3);
    // SP colours: one finite value per vertex (boundary nodes, SP = infinity, at the top); the
    // colour map tops out at the 95th percentile.
    ASSERT_EQ(erased->vertex_scalar.size(), erased->mesh.n_vertices());
    std::size_t above = 0;
    for (float sp : erased->vertex_scalar) {
        EXPECT_TRUE(std::isfinite(sp) && sp >= 0.0f) << sp;
        above += sp > erased->scalar_max;
    }
    EXPECT_GT(erased->scalar_max, 0.0f);
    EXPECT_LE(above, erased->vertex_scalar.size() / 20 + 1);
}

// From a store the erase stage reads the store whole and bounds every sample too.
TEST(ViewWorker, EraseStageFromAStoreBoundsEverySample) {
    const Heightfield hf = load_heightfield(test::asset("dem_squared.tif"));
    const std::string path = test::temp_dir() + "/squared.tlq";
    write_store(QuadTree(hf), path);
    SceneInfo info;
    auto engine = open_scene(path, info);
    const View v = oblique_view(info);
    LodSettings s;
    s.tol_px = 1.0;
    s.stages = LodStages::retrieve_erase;
    const auto erased = engine->compute(v, s);
    ErrorOptions eo;
    eo.model = Significance::screen(v);
    const TinError measured = measure_error(hf, erased->mesh, eo);
    EXPECT_EQ(measured.uncovered, 0);
    EXPECT_LE(measured.max_screen_px, s.tol_px);
    EXPECT_LT(std::size_t(erased->nodes), std::size_t(hf.size()) / 4);
}

TEST(ViewWorker, RefineStageKeepsOneTinThatFollowsTheEye) {
    SceneInfo info;
    auto engine = open_scene(test::asset("dem_squared.tif"), info);
    const Heightfield hf = load_heightfield(test::asset("dem_squared.tif"));
    View high;
    high.viewport_w = 800;
    high.viewport_h = 600;
    high.eye = {0.5 * info.hi.x, -0.5 * info.hi.y, info.hi.z + 2.0 * info.hi.x};
    high.at = 0.5 * (info.lo + info.hi);
    View low = high;
    low.eye = {0.5 * info.hi.x, 0.2 * info.hi.y, info.hi.z + 50.0};
    LodSettings s;
    s.stages = LodStages::refine;
    const auto far = engine->compute(high, s);
    const auto near = engine->compute(low, s);
    EXPECT_GT(near->nodes, far->nodes) << "descending recovers nodes";
    for (const auto &[r, v] : {std::pair{far.get(), &high}, std::pair{near.get(), &low}}) {
        ErrorOptions eo;
        eo.model = Significance::screen(*v);
        EXPECT_LE(measure_error(hf, r->mesh, eo).max_screen_px, s.tol_px);
        EXPECT_EQ(r->triangles, std::int64_t(r->mesh.n_faces()));
    }
}
