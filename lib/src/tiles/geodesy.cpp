// WGS84 geometry of the tile headers (geodesy.hpp) and the tiling scheme (tiles.hpp).
#include "geodesy.hpp"

#include "tinlod/tiles.hpp"

#include <algorithm>
#include <cmath>

namespace tinlod {

GeoRect tile_rect(const TileId &tile) {
    // Every edge is -180 + k * size or -90 + k * size with a whole k, so the tiles on both sides
    // of an edge compute the same double for it.
    const double size = 180.0 / std::ldexp(1.0, tile.z);
    return {-180.0 + double(tile.x) * size, -90.0 + double(tile.y) * size,
            -180.0 + double(tile.x + 1) * size, -90.0 + double(tile.y + 1) * size};
}

double level_error(int z) {
    // CesiumJS: TerrainProvider.heightmapTerrainQuality (0.25), a 65-sample heightmap tile and 2
    // tiles across at level 0 (CesiumTerrainProvider), halved at every level.
    const double level0 = tiles::k_wgs84_a * 2.0 * M_PI * 0.25 / (65.0 * 2.0);
    return level0 / std::ldexp(1.0, z);
}

namespace tiles {

glm::dvec3 ecef(double lon, double lat, double h) {
    const double l = lon * M_PI / 180.0, p = lat * M_PI / 180.0;
    const double e2 = 1.0 - (k_wgs84_b * k_wgs84_b) / (k_wgs84_a * k_wgs84_a);
    const double n = k_wgs84_a / std::sqrt(1.0 - e2 * std::sin(p) * std::sin(p));
    return {(n + h) * std::cos(p) * std::cos(l), (n + h) * std::cos(p) * std::sin(l),
            (n * (1.0 - e2) + h) * std::sin(p)};
}

std::array<glm::dvec3, 3> enu_frame(double lon, double lat) {
    const double l = lon * M_PI / 180.0, p = lat * M_PI / 180.0;
    return {glm::dvec3(-std::sin(l), std::cos(l), 0.0),
            glm::dvec3(-std::sin(p) * std::cos(l), -std::sin(p) * std::sin(l), std::cos(p)),
            glm::dvec3(std::cos(p) * std::cos(l), std::cos(p) * std::sin(l), std::sin(p))};
}

Sphere bounding_sphere(std::span<const glm::dvec3> points) {
    Sphere s;
    if (points.empty())
        return s;
    glm::dvec3 lo = points[0], hi = points[0];
    for (const glm::dvec3 &p : points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    s.centre = 0.5 * (lo + hi);
    for (const glm::dvec3 &p : points)
        s.radius = std::max(s.radius, glm::length(p - s.centre));
    return s;
}

glm::dvec3 horizon_occlusion_point(std::span<const glm::dvec3> points, const glm::dvec3 &direction,
                                   double min_height) {
    glm::dvec3 radii(k_wgs84_a, k_wgs84_a, k_wgs84_b);
    if (min_height < 0.0 && k_wgs84_b > -min_height)
        radii += glm::dvec3(min_height);
    const glm::dvec3 dir = glm::normalize(direction / radii);
    double magnitude = 0.0;
    bool found = true;
    for (const glm::dvec3 &p : points) {
        const glm::dvec3 scaled = p / radii;
        double m2 = glm::dot(scaled, scaled);
        double m = std::sqrt(m2);
        const glm::dvec3 unit = scaled / m;
        // Points under the ellipsoid count as on it.
        m2 = std::max(1.0, m2);
        m = std::max(1.0, m);
        const double cos_a = glm::dot(unit, dir);
        const double sin_a = glm::length(glm::cross(unit, dir));
        const double cos_b = 1.0 / m, sin_b = std::sqrt(m2 - 1.0) * cos_b;
        const double candidate = 1.0 / (cos_a * cos_b - sin_a * sin_b);
        if (!(candidate >= 0.0) || std::isinf(candidate)) {
            found = false;
            break;
        }
        magnitude = std::max(magnitude, candidate);
    }
    // The magnitude a point exactly on the hemisphere's rim gives (1 / cos(90 degrees)).
    constexpr double k_rim = 1.0e16;
    if (!found || !(magnitude > 0.0))
        magnitude = k_rim;
    return dir * magnitude;
}

std::array<std::uint8_t, 2> oct_encode(const glm::dvec3 &n) {
    const double l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    double x = n.x / l1, y = n.y / l1;
    if (n.z < 0.0) {
        const double ox = x, oy = y;
        x = (1.0 - std::abs(oy)) * (ox < 0.0 ? -1.0 : 1.0);
        y = (1.0 - std::abs(ox)) * (oy < 0.0 ? -1.0 : 1.0);
    }
    // CesiumJS's toSNorm: Math.round((clamp(v, -1, 1) * 0.5 + 0.5) * 255); Math.round rounds
    // halves up.
    const auto snorm = [](double v) {
        return std::uint8_t(std::floor((std::clamp(v, -1.0, 1.0) * 0.5 + 0.5) * 255.0 + 0.5));
    };
    return {snorm(x), snorm(y)};
}

} // namespace tiles
} // namespace tinlod
