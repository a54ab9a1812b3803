// Elevation rasters: the Heightfield and its loaders (SRTM .hgt; PNG and plain GeoTIFF through
// libpng and libtiff, everything else through OpenImageIO; georeferencing from the GeoTIFF tags,
// WGS 84 and its UTM zones as PROJ computes them, other CRSs through PROJ; Mapbox Terrain-RGB).
#pragma once

#include <cstdint>
#include <memory>
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

// A DEM read by windows of rows, never whole: what `tinlod tiles` reads when the DEMs exceed its
// memory (docs/tiles.md, "Memory"). Opening it reads the file once, a strip at a time, to find its
// voids and the rows and columns of voids at its edges that load_heightfield crops away.
// .hgt files are read directly, every other raster through OpenImageIO (its scanline reads, which
// read a tiled file's tiles). Voids are filled by strips of k_fill_rows rows, each filled as
// load_heightfield fills the whole raster but over the strip and k_fill_margin rows on both
// sides: a void region within the margin (with a row of valid samples round it) is filled
// exactly as load_heightfield fills it, a larger one from what the margin shows. Either way a
// sample's height does not depend on which rows were asked for.
class DemWindows {
  public:
    static constexpr int k_fill_rows = 256;
    static constexpr int k_fill_margin = 256;
    // Throws Error naming the file as load_heightfield does (options.terrain_rgb is refused).
    DemWindows(const std::string &path, const LoadOptions &options);
    ~DemWindows();
    DemWindows(const DemWindows &) = delete;
    DemWindows &operator=(const DemWindows &) = delete;
    // What load_heightfield would return but the heights (z and void_mask are empty).
    const Heightfield &grid() const;
    // Heights of rows [r0, r1) (row 0 south, as a Heightfield's), every column; voids filled.
    std::vector<float> rows(int r0, int r1) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Samples of a raster (width * height) from its header, without reading its samples.
std::int64_t raster_samples(const std::string &path);

// Largest raster we accept (samples); checked before allocating.
inline constexpr std::int64_t k_max_raster_samples = std::int64_t{1} << 31;

} // namespace tinlod
