// Camera paths: the CSV that `tinlod fly` reads and the viewer records and replays.
// Header: t,eye_x,eye_y,eye_z,at_x,at_y,at_z — one keyframe per line, t in seconds, increasing.
#pragma once

#include "tinlod/view.hpp"

#include <string>
#include <vector>

namespace tinlod {

struct Keyframe {
    double t = 0.0; // seconds
    glm::dvec3 eye{0.0};
    glm::dvec3 at{0.0};
};

struct CameraPath {
    std::vector<Keyframe> keys; // t strictly increasing, at least one

    double duration() const { return keys.empty() ? 0.0 : keys.back().t - keys.front().t; }
    // Eye and look-at point at time t (linear between keyframes, clamped at the ends); the other
    // View fields come from `base`.
    View at_time(double t, const View &base) const;
    // `frames` views evenly spaced over the path (frames >= 1; 1 gives the first keyframe).
    std::vector<View> sample(int frames, const View &base) const;
};

// Reads a path CSV; throws Error naming the file and line on a wrong header, a malformed or
// non-finite number, t not increasing, an eye equal to its look-at point, or no keyframe.
CameraPath read_camera_path(const std::string &path);
// Parses CSV text (`source` names it in errors).
CameraPath parse_camera_path(const std::string &text, const std::string &source);
// Writes a path CSV atomically (the header above, 17 significant digits).
void write_camera_path(const CameraPath &path, const std::string &file);

} // namespace tinlod
