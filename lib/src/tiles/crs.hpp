// The one place the tile build asks PROJ anything: points from one CRS to another.
#pragma once

#include <glm/glm.hpp>

#include <span>
#include <string>
#include <vector>

namespace tinlod::tiles {

// Transforms `points` (x east / longitude first, y north / latitude second, whatever the CRS's own
// axis order) from EPSG:from to EPSG:to; a point PROJ cannot transform comes back as NaN. Throws
// Error(subject, ...) when PROJ knows no transformation between the two.
std::vector<glm::dvec2> transform_points(int from, int to, std::span<const glm::dvec2> points,
                                         const std::string &subject);

} // namespace tinlod::tiles
