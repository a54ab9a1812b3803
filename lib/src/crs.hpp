// The coordinate reference systems of georeferenced rasters. WGS 84 (EPSG:4326) and its UTM zones
// (EPSG:32601-32660 north, 32701-32760 south), by far the commonest, are interpreted here exactly
// as PROJ 9 interprets them, so that reading an SRTM tile or a WGS 84 GeoTIFF loads no PROJ; every
// other CRS goes to PROJ (backends::crs_library()).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace tinlod::crs {

// Throws Error(path, ...) when EPSG:`epsg` is not a CRS of the kind the file says (`geographic`
// or projected), or is projected in other units than metres.
void check(const std::string &path, int epsg, bool geographic);

// (longitude, latitude) points in degrees of EPSG:`from`, in EPSG:`to`: what PROJ's
// proj_create_crs_to_crs gives, non-finite where the point is outside the projection's domain.
// Throws Error(path, ...) when there is no transformation.
std::vector<std::array<double, 2>> transform(const std::string &path, int from, int to,
                                             const std::vector<std::array<double, 2>> &points);

// A WGS 84 point (degrees) in UTM zone `zone` (1..60), metres: PROJ 9's pipeline
// "+proj=unitconvert +xy_in=deg +xy_out=rad +step +proj=utm +zone=Z [+south] +ellps=WGS84"
// (Poder/Engsager's transverse Mercator), to the last bit; HUGE_VAL outside its domain.
std::array<double, 2> wgs84_to_utm(int zone, bool south, double lon, double lat);

} // namespace tinlod::crs
