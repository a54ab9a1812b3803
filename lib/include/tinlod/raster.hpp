// Elevation rasters: the Heightfield and its loaders (SRTM .hgt; PNG and plain GeoTIFF through
// libpng and libtiff, everything else through OpenImageIO; georeferencing from the GeoTIFF tags,
// WGS 84 and its UTM zones as PROJ computes them, other CRSs through PROJ; Mapbox Terrain-RGB).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tinlod {

// A regular grid of elevations. Row 0 is the SOUTH edge (files are flipped on load), so sample
// (c, r) stands at local world coordinates (c * dx, r * dy, z). Node id of a sample:
// r * width + c.
struct Heightfield {
    int width = 0;
    int height = 0;
    std::vector<float> z;  // width*height elevations in world units (metres), row-major
    double dx = 1.0;       // ground spacing east, world units
    double dy = 1.0;       // ground spacing north, world units
    double origin_x = 0.0; // CRS coordinates of sample (0, 0) (the SW sample), for reference
    double origin_y = 0.0;
    std::string crs; // description of the CRS of the local frame, e.g. "EPSG:32631 (UTM 31N)"
    // The file's own CRS (georeferenced rasters; 0 otherwise) and where sample (c, r) stands in
    // it: (native_x0 + c * native_dx, native_y0 + r * native_dy), degrees for a geographic CRS.
    // The local frame above is metric; a geographic raster's samples are a lattice in degrees.
    int native_epsg = 0;
    bool native_geographic = false;
    double native_x0 = 0.0, native_y0 = 0.0, native_dx = 0.0, native_dy = 0.0;
    std::vector<std::uint8_t> void_mask; // empty, or 1 where the sample was a void (now filled)
    std::int64_t voids = 0;              // void samples in the file (cropped ones included)
    std::int64_t filled = 0;             // number of voids filled from valid neighbours
    std::int64_t cropped = 0; // samples cut away: whole rows/columns of voids at the edges

    float at(int c, int r) const { return z[static_cast<std::size_t>(r) * width + c]; }
    float &at(int c, int r) { return z[static_cast<std::size_t>(r) * width + c]; }
    std::int64_t size() const { return static_cast<std::int64_t>(width) * height; }
    float min_z() const;
    float max_z() const;
};

struct LoadOptions {
    // Ground size of a pixel, for rasters without georeferencing only (default 1); a
    // georeferenced raster refuses it, and an .hgt file without an SRTM tile name needs it.
    std::optional<double> cell;
    double zscale = 1.0;      // multiplies every elevation
    bool terrain_rgb = false; // decode RGB as Mapbox Terrain-RGB: (R*65536 + G*256 + B)/10 - 10000
    bool fill_voids = true;   // fill voids from valid neighbours (else: throw if any void)
    // Memory the caller's whole run holds per raster sample at its peak, loading included, bytes
    // (0: the load alone); with the raster's size it makes the estimate checked before loading.
    double bytes_per_sample = 0;
    double max_memory_mb = 0; // refuse a raster whose estimate exceeds this, MiB (0: this
                              // machine's physical memory)
};

// Loads a DEM by extension/content: .hgt, or anything OpenImageIO reads. Throws Error naming the
// file on anything unusable (unreadable, truncated, NaN, all-void, absurd size, more memory than
// allowed, a colour image, georeferencing it cannot honour). Alpha 0 and a PNG's tRNS key are
// voids, as is the nodata value.
Heightfield load_heightfield(const std::string &path, const LoadOptions &options = {});

// Largest raster we accept (samples); checked before allocating.
inline constexpr std::int64_t k_max_raster_samples = std::int64_t{1} << 31;

} // namespace tinlod
