// WGS84 geometry of the tile headers: Earth-centred positions, the bounding sphere, the horizon
// occlusion point (CesiumJS's EllipsoidalOccluder), oct-encoded normals (Cigolle et al. 2014, as
// CesiumJS's AttributeCompression.octEncode).
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>

namespace tinlod::tiles {

inline constexpr double k_wgs84_a = 6378137.0;          // equatorial radius, metres
inline constexpr double k_wgs84_b = 6356752.3142451793; // polar radius, metres
inline constexpr int k_quantized_max = 32767;           // u, v and height run 0 .. this

// Earth-centred, Earth-fixed position of longitude/latitude (degrees) at height h (metres).
glm::dvec3 ecef(double lon, double lat, double h);

// The unit vectors east, north and up (the ellipsoid's normal) at longitude/latitude, degrees.
std::array<glm::dvec3, 3> enu_frame(double lon, double lat);

struct Sphere {
    glm::dvec3 centre{0.0};
    double radius = 0.0;
};

// A sphere holding every point: the centre of their bounding box, the largest distance from it.
Sphere bounding_sphere(std::span<const glm::dvec3> points);

// The horizon occlusion point of `points` in the ellipsoid-scaled frame, computed as CesiumJS's
// EllipsoidalOccluder.computeHorizonCullingPointFromVerticesPossiblyUnderEllipsoid (the ellipsoid
// shrunk by min_height when that is below 0), along `direction`. Where CesiumJS finds none (a tile
// wider than a hemisphere seen from its centre, level 0), the point is far out along `direction`:
// the limit of the construction, hidden only when the whole tile is.
glm::dvec3 horizon_occlusion_point(std::span<const glm::dvec3> points, const glm::dvec3 &direction,
                                   double min_height);

// A unit vector oct-encoded into two bytes (range 255).
std::array<std::uint8_t, 2> oct_encode(const glm::dvec3 &n);

} // namespace tinlod::tiles
