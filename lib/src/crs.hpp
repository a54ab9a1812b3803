// The coordinate reference systems of georeferenced rasters. WGS 84 (EPSG:4326) and its UTM zones
// (EPSG:32601-32660 north, 32701-32760 south), by far the commonest, are interpreted here exactly
// as PROJ 9 interprets them, so that reading an SRTM tile or a WGS 84 GeoTIFF loads no PROJ; every
// other CRS goes to PROJ (backends::crs_library()).
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace tinlod::backends {
class CrsTransformation;
}

namespace tinlod::crs {

// Throws Error(path, ...) when EPSG:`epsg` is not a CRS of the kind the file says (`geographic`
// or projected), or is projected in other units than metres.
void check(const std::string &path, int epsg, bool geographic);

// The transformation from EPSG:`from` to EPSG:`to` as PROJ's proj_create_crs_to_crs makes it,
// made once and applied to many points, x east / longitude first whatever the CRSs' axis order.
class Transformation {
  public:
    // Throws Error(path, ...) when there is no transformation between the two.
    Transformation(const std::string &path, int from, int to);
    ~Transformation();
    Transformation(const Transformation &) = delete;
    Transformation &operator=(const Transformation &) = delete;
    // The points transformed; one outside the transformation's domain comes back as NaN.
    std::vector<glm::dvec2> apply(std::span<const glm::dvec2> points) const;

  private:
    int utm_zone_ = 0; // from WGS 84 to this UTM zone, without PROJ
    bool south_ = false;
    std::unique_ptr<backends::CrsTransformation> proj_; // else this, or null for the identity
};

// A WGS 84 point (degrees) in UTM zone `zone` (1..60), metres: PROJ 9's pipeline
// "+proj=unitconvert +xy_in=deg +xy_out=rad +step +proj=utm +zone=Z [+south] +ellps=WGS84"
// (Poder/Engsager's transverse Mercator), to the last bit; HUGE_VAL outside its domain.
std::array<double, 2> wgs84_to_utm(int zone, bool south, double lon, double lat);

} // namespace tinlod::crs
