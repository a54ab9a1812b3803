// The camera: eye, a point it looks toward, vertical field of view and viewport (docs/method.md).
// All world coordinates are the local frame of the terrain: x east, y north, z up, metres.
#pragma once

#include <glm/glm.hpp>

#include <string>

namespace tinlod {

struct View {
    glm::dvec3 eye{0.0, 0.0, 1.0};
    glm::dvec3 at{0.0, 1.0, 0.0}; // the observation axis runs from eye through at
    double fov_deg = 60.0;        // vertical field of view, degrees, in (0, 180)
    int viewport_w = 1920;        // pixels
    int viewport_h = 1080;        // pixels

    // Pixels per unit of world deviation at unit distance: a deviation d at distance D shows as
    // d * k() / D pixels. k = viewport_h / (2 tan(fov/2)).
    double k() const;
    // Unit vector of the observation axis.
    glm::dvec3 axis() const;
    // The projection frame: the axis and the screen's right and up as unit vectors (up is z, or
    // north when the axis is vertical). The one frame of in_frustum, the screen weight, the
    // retrieval's frustum planes; view_matrix() takes the same up.
    struct Frame {
        glm::dvec3 forward, right, up;
    };
    Frame frame() const;
    // Right-handed look-at matrix with z up (y up when the axis is vertical).
    glm::dmat4 view_matrix() const;
    // Perspective projection for the viewport aspect; near/far in world units.
    glm::dmat4 projection_matrix(double near, double far) const;
    // True when p lies inside the (infinite-depth) view pyramid, with `margin_px` pixels of slack.
    bool in_frustum(const glm::dvec3 &p, double margin_px = 0.0) const;
    // Screen-space size in pixels of a world deviation `delta` seen at point p (distance to eye).
    double screen_px(double delta, const glm::dvec3 &p) const;
};

// Checks the view for NaN, a zero-length axis, fov outside (0, 180), empty viewport; throws Error
// naming `subject` (e.g. "--eye") when it is unusable.
void validate(const View &view, const std::string &subject = "view");

// Parses "X,Y,Z" (throws Error naming `option` on bad text).
glm::dvec3 parse_vec3(const std::string &text, const std::string &option);
// Parses "WxH".
void parse_viewport(const std::string &text, int &w, int &h);

} // namespace tinlod
