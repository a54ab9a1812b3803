// The viewer's camera control apart from any window: fly and orbit navigation driven by key and
// mouse events, terrain following, and recording / replaying a camera path (the CSV of
// camera_path.hpp). Angles in radians, lengths in world units, times in seconds.
#pragma once

#include "tinlod/camera_path.hpp"
#include "tinlod/view.hpp"

#include <glm/glm.hpp>

#include <optional>

namespace tinlod::viewer {

// Which movement keys are held during a frame.
struct MoveKeys {
    bool forward = false; // W
    bool back = false;    // S
    bool left = false;    // A
    bool right = false;   // D
    bool up = false;      // E or space
    bool down = false;    // Q or ctrl
};

enum class NavMode {
    fly,   // the eye moves, the mouse turns the head
    orbit, // the eye circles the pivot (the focal point) at a fixed distance
};

struct ControlOptions {
    double look_rad_per_px = 0.004;   // mouse look and orbit: rotation per pixel dragged
    double max_pitch_rad = 1.5533430; // |pitch| limit (89 degrees): the axis never turns vertical
    double wheel_factor = 1.25;       // speed (fly) or distance (orbit) change per wheel step
    double orbit_rad_per_s = 1.0;     // orbit mode: A/D and Q/E turn rate
};

// The camera as eye + heading: yaw counter-clockwise from +x (east) in the xy plane, pitch up from
// the horizon. In orbit mode the eye sits at `distance` from the pivot, looking at it.
class CameraControl {
  public:
    explicit CameraControl(const ControlOptions &options = {}) : options_(options) {}

    // Places the camera at `eye` looking toward `at` (eye != at); the look distance |at - eye| is
    // kept for View::at. Pitch is clamped to the limit.
    void look_at(const glm::dvec3 &eye, const glm::dvec3 &at);
    // Remembers the current camera as the one reset() returns to.
    void set_home() { home_ = State{eye_, yaw_, pitch_, look_distance_, speed_}; }
    void reset();

    // Orbit mode turns around `pivot` (the focal point); entering it points the camera at the pivot
    // without moving the eye.
    void set_mode(NavMode mode, const glm::dvec3 &pivot);
    NavMode mode() const { return mode_; }

    // Advances by dt seconds with `keys` held. Fly: W/S along the view direction, A/D sideways
    // (horizontal), E/Q straight up/down, each at speed() units per second. Orbit: W/S move toward
    // / away from the pivot (distance changes by a factor e^(dt)), A/D turn around it, E/Q raise
    // and lower the eye on the sphere.
    void update(const MoveKeys &keys, double dt);
    // Mouse moved by (dx, dy) pixels (x right, y down) with the look button held. Fly: turns the
    // head (yaw and pitch). Orbit: moves the eye around the pivot at constant distance.
    void drag(double dx_px, double dy_px);
    // Mouse wheel: fly mode multiplies speed by wheel_factor^steps; orbit divides the distance.
    void scroll(double steps);

    // Terrain following: lifts the eye to at least ground_z + clearance (orbit keeps its pivot).
    void keep_above(double ground_z, double clearance);

    // The View of the camera: eye, at = eye + look_distance * direction; the rest from `base`.
    View view(const View &base) const;

    const glm::dvec3 &eye() const { return eye_; }
    glm::dvec3 direction() const;
    double yaw() const { return yaw_; }
    double pitch() const { return pitch_; }
    const glm::dvec3 &pivot() const { return pivot_; }
    double speed() const { return speed_; } // fly speed, world units per second
    void set_speed(double speed) { speed_ = speed; }
    double look_distance() const { return look_distance_; }
    void set_look_distance(double d) { look_distance_ = d; }

  private:
    struct State {
        glm::dvec3 eye{0.0};
        double yaw = 0.0, pitch = 0.0, look_distance = 1.0, speed = 1.0;
    };
    void place_on_orbit(double distance);

    ControlOptions options_;
    glm::dvec3 eye_{0.0, 0.0, 1.0};
    double yaw_ = 0.0, pitch_ = 0.0;
    double look_distance_ = 1.0;
    double speed_ = 1.0;
    NavMode mode_ = NavMode::fly;
    glm::dvec3 pivot_{0.0};
    State home_;
};

// Records the camera as keyframes while the user flies: one keyframe per `interval` seconds of
// recording time (the first at t = 0), skipping samples whose eye and at did not move, so a replay
// through CameraPath::at_time follows the flight.
class PathRecorder {
  public:
    explicit PathRecorder(double interval = 0.25) : interval_(interval) {}
    void start(double now);
    // Offers the camera at clock time `now`; keeps it as a keyframe when due.
    void sample(double now, const View &view);
    // Ends the recording; the path has at least one keyframe when anything was sampled.
    CameraPath stop(double now, const View &view);
    bool recording() const { return recording_; }
    const CameraPath &path() const { return path_; }

  private:
    double interval_;
    double start_ = 0.0;
    bool recording_ = false;
    CameraPath path_;
};

// Replays a path on the clock: time 0 is the first keyframe.
class PathPlayer {
  public:
    void start(CameraPath path, double now);
    void stop() { playing_ = false; }
    bool playing() const { return playing_; }
    // The view at clock time `now`, or nothing once the path has ended (playback then stops).
    std::optional<View> view(double now, const View &base);
    const CameraPath &path() const { return path_; }

  private:
    CameraPath path_;
    double start_ = 0.0;
    bool playing_ = false;
};

} // namespace tinlod::viewer
