// Fly and orbit navigation, path recording and replay (camera_control.hpp).
#include "camera_control.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tinlod::viewer {

namespace {

glm::dvec3 heading(double yaw, double pitch) {
    return {std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch)};
}

} // namespace

void CameraControl::look_at(const glm::dvec3 &eye, const glm::dvec3 &at) {
    const glm::dvec3 d = at - eye;
    const double len = glm::length(d);
    assert(len > 0.0);
    eye_ = eye;
    look_distance_ = len;
    yaw_ = std::atan2(d.y, d.x);
    pitch_ = std::clamp(std::asin(std::clamp(d.z / len, -1.0, 1.0)), -options_.max_pitch_rad,
                        options_.max_pitch_rad);
}

void CameraControl::reset() {
    eye_ = home_.eye;
    yaw_ = home_.yaw;
    pitch_ = home_.pitch;
    look_distance_ = home_.look_distance;
    speed_ = home_.speed;
    mode_ = NavMode::fly;
}

glm::dvec3 CameraControl::direction() const { return heading(yaw_, pitch_); }

void CameraControl::set_mode(NavMode mode, const glm::dvec3 &pivot) {
    mode_ = mode;
    if (mode != NavMode::orbit)
        return;
    pivot_ = pivot;
    const double distance = glm::length(pivot - eye_);
    if (distance > 0.0)
        look_at(eye_, pivot);
    place_on_orbit(look_distance_);
}

// Puts the eye on the sphere of radius `distance` around the pivot, opposite the view direction.
void CameraControl::place_on_orbit(double distance) {
    look_distance_ = distance;
    eye_ = pivot_ - distance * direction();
}

void CameraControl::update(const MoveKeys &keys, double dt) {
    const double f = (keys.forward ? 1.0 : 0.0) - (keys.back ? 1.0 : 0.0);
    const double s = (keys.right ? 1.0 : 0.0) - (keys.left ? 1.0 : 0.0);
    const double u = (keys.up ? 1.0 : 0.0) - (keys.down ? 1.0 : 0.0);
    if (mode_ == NavMode::fly) {
        const glm::dvec3 right(std::sin(yaw_), -std::cos(yaw_), 0.0);
        eye_ += speed_ * dt * (f * direction() + s * right + u * glm::dvec3(0.0, 0.0, 1.0));
        return;
    }
    yaw_ += s * options_.orbit_rad_per_s * dt;
    pitch_ = std::clamp(pitch_ - u * options_.orbit_rad_per_s * dt, -options_.max_pitch_rad,
                        options_.max_pitch_rad);
    place_on_orbit(look_distance_ * std::exp(-f * dt));
}

void CameraControl::drag(double dx_px, double dy_px) {
    const double a = options_.look_rad_per_px;
    yaw_ -= dx_px * a;
    pitch_ = std::clamp(pitch_ - dy_px * a, -options_.max_pitch_rad, options_.max_pitch_rad);
    if (mode_ == NavMode::orbit)
        place_on_orbit(look_distance_);
}

void CameraControl::scroll(double steps) {
    const double factor = std::pow(options_.wheel_factor, steps);
    if (mode_ == NavMode::fly)
        speed_ *= factor;
    else
        place_on_orbit(look_distance_ / factor);
}

void CameraControl::keep_above(double ground_z, double clearance) {
    const double floor = ground_z + clearance;
    if (eye_.z >= floor)
        return;
    eye_.z = floor;
    if (mode_ == NavMode::orbit && glm::length(pivot_ - eye_) > 0.0)
        look_at(eye_, pivot_);
}

View CameraControl::view(const View &base) const {
    View v = base;
    v.eye = eye_;
    v.at = eye_ + look_distance_ * direction();
    return v;
}

void PathRecorder::start(double now) {
    start_ = now;
    recording_ = true;
    path_ = CameraPath{};
}

void PathRecorder::sample(double now, const View &view) {
    if (!recording_)
        return;
    const double t = now - start_;
    if (!path_.keys.empty()) {
        const Keyframe &last = path_.keys.back();
        if (t < last.t + interval_ || (last.eye == view.eye && last.at == view.at))
            return;
    }
    path_.keys.push_back({path_.keys.empty() ? 0.0 : t, view.eye, view.at});
}

CameraPath PathRecorder::stop(double now, const View &view) {
    if (recording_ && !path_.keys.empty()) {
        const Keyframe &last = path_.keys.back();
        const double t = now - start_;
        if (t > last.t && (last.eye != view.eye || last.at != view.at))
            path_.keys.push_back({t, view.eye, view.at});
    }
    recording_ = false;
    return path_;
}

void PathPlayer::start(CameraPath path, double now) {
    assert(!path.keys.empty());
    path_ = std::move(path);
    start_ = now;
    playing_ = true;
}

std::optional<View> PathPlayer::view(double now, const View &base) {
    if (!playing_)
        return std::nullopt;
    const double t = path_.keys.front().t + (now - start_);
    if (t > path_.keys.back().t) {
        playing_ = false;
        return path_.at_time(path_.keys.back().t, base);
    }
    return path_.at_time(t, base);
}

} // namespace tinlod::viewer
