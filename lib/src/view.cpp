// Camera math for View (GLM).
#include "tinlod/view.hpp"
#include "tinlod/error.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace tinlod {

double View::k() const { return viewport_h / (2.0 * std::tan(glm::radians(fov_deg) / 2.0)); }

glm::dvec3 View::axis() const { return glm::normalize(at - eye); }

static glm::dvec3 up_for(const glm::dvec3 &axis) {
    // Looking straight down (or up) the z-up vector is degenerate: use north as up instead.
    return std::abs(axis.z) > 0.999 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
}

View::Frame View::frame() const {
    const glm::dvec3 f = axis();
    const glm::dvec3 r = glm::normalize(glm::cross(f, up_for(f)));
    return {f, r, glm::cross(r, f)};
}

glm::dmat4 View::view_matrix() const { return glm::lookAt(eye, at, up_for(axis())); }

glm::dmat4 View::projection_matrix(double near, double far) const {
    return glm::perspective(glm::radians(fov_deg), double(viewport_w) / viewport_h, near, far);
}

bool View::in_frustum(const glm::dvec3 &p, double margin_px) const {
    const Frame fr = frame();
    const glm::dvec3 d = p - eye;
    const double depth = glm::dot(d, fr.forward);
    if (depth <= 0.0)
        return false;
    const double kk = k();
    const double sx = glm::dot(d, fr.right) * kk / depth;
    const double sy = glm::dot(d, fr.up) * kk / depth;
    return std::abs(sx) <= viewport_w / 2.0 + margin_px &&
           std::abs(sy) <= viewport_h / 2.0 + margin_px;
}

double View::screen_px(double delta, const glm::dvec3 &p) const {
    const double d = glm::length(p - eye);
    return d > 0.0 ? delta * k() / d : INFINITY;
}

void validate(const View &view, const std::string &subject) {
    auto finite = [](const glm::dvec3 &v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    if (!finite(view.eye))
        throw Error(subject, "eye is not a finite point");
    if (!finite(view.at))
        throw Error(subject, "look-at point is not a finite point");
    if (glm::length(view.at - view.eye) <= 0.0)
        throw Error(subject, "eye and look-at point coincide");
    if (!(view.fov_deg > 0.0 && view.fov_deg < 180.0))
        throw Error(subject, "field of view must be in (0, 180) degrees");
    if (view.viewport_w <= 0 || view.viewport_h <= 0 || view.viewport_w > 65536 ||
        view.viewport_h > 65536)
        throw Error(subject, "viewport must be between 1x1 and 65536x65536 pixels");
}

glm::dvec3 parse_vec3(const std::string &text, const std::string &option) {
    double v[3];
    char tail = 0;
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &tail) != 3)
        throw Error(option, "expected X,Y,Z, got '" + text + "'");
    for (double x : v)
        if (!std::isfinite(x))
            throw Error(option, "coordinates must be finite, got '" + text + "'");
    return {v[0], v[1], v[2]};
}

void parse_viewport(const std::string &text, int &w, int &h) {
    // Digits only, at most 6 each: scanf's %d wrapped 4294967297 to 1.
    const auto side = [](const std::string &digits) {
        if (digits.empty() || digits.size() > 6 ||
            digits.find_first_not_of("0123456789") != std::string::npos)
            return 0;
        return std::stoi(digits);
    };
    const auto x = text.find('x');
    w = x == std::string::npos ? 0 : side(text.substr(0, x));
    h = x == std::string::npos ? 0 : side(text.substr(x + 1));
    if (w <= 0 || h <= 0 || w > 65536 || h > 65536)
        throw Error("--viewport",
                    "expected WxH in pixels, each from 1 to 65536, got '" + text + "'");
}

} // namespace tinlod
