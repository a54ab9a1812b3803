// The one place the tile build asks PROJ anything: points from one CRS to another.
#pragma once

#include <glm/glm.hpp>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace tinlod::tiles {

// A transformation from EPSG:from to EPSG:to, made once (PROJ's set-up reads its database) and
// applied to many points. Points are x east / longitude first, y north / latitude second, whatever
// the CRS's own axis order.
class CrsTransform {
  public:
    // Throws Error(subject, ...) when PROJ knows no transformation between the two.
    CrsTransform(int from, int to, const std::string &subject);
    ~CrsTransform();
    CrsTransform(const CrsTransform &) = delete;
    CrsTransform &operator=(const CrsTransform &) = delete;
    // The points transformed; one PROJ cannot transform comes back as NaN.
    std::vector<glm::dvec2> apply(std::span<const glm::dvec2> points) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace tinlod::tiles
