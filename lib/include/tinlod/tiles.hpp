// Terrain tiles for streaming clients: a Cesium quantized-mesh-1.0 pyramid in the geographic TMS
// scheme (EPSG:4326, 2 x 1 tiles at level 0), each tile a TIN within the geometric error CesiumJS
// assumes for its level at every DEM sample inside it, and same-level neighbours sharing their
// common edge vertex for vertex (no cracks).
//
// Specification: github.com/CesiumGS/quantized-mesh (header, zig-zag delta vertices, high-water-
// mark indices, edge lists, the oct-encoded normals extension, layer.json); the level's error is
// CesiumJS's TerrainProvider.getEstimatedLevelZeroGeometricErrorForAHeightmap(WGS84, 65, 2) / 2^z.
//
// How a tile is made (docs/tiles.md): the DEMs are one lattice of posts in longitude and latitude
// (a geographic DEM's own samples; any other is resampled onto such a lattice). Each tile edge is
// a polyline simplified once from the edge's own samples (the lattice interpolated along the edge
// line), so both tiles that share it hold the same vertices. Inside, the lattice posts at least one
// u/v unit from the edges are a Heightfield, meshed by greedy insertion and then the node erase
// (vertical model) to the bound; a strip of triangles joins its outline to the edge polylines, and
// no post lies strictly inside that strip. The tile is then quantized, measured at every covered
// post inside it as a decoder sees it; where a post is over the bound it becomes a vertex (the
// repair, in exact u/v) and the triangles round it are measured again.
// A tile is a pure function of the lattice, its level and its address: built alone it is
// byte-identical to the same tile built in a whole run.
#pragma once

#include "tinlod/raster.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tinlod {

// ---- The tiling scheme ------------------------------------------------------------------------

struct TileId {
    int z = 0;          // level
    std::int64_t x = 0; // column from the west (-180 degrees), 0 .. 2^(z+1) - 1
    std::int64_t y = 0; // row from the south (-90 degrees, TMS), 0 .. 2^z - 1
    bool operator==(const TileId &) const = default;
};

struct GeoRect {
    double west = 0, south = 0, east = 0, north = 0; // degrees
};

GeoRect tile_rect(const TileId &tile);

// Deepest level accepted: the u/v grid of a tile there is finer than a millimetre.
inline constexpr int k_max_tile_level = 24;

// The maximum geometric error CesiumJS assumes for a quantized-mesh tile of level z, metres:
// WGS84 maximum radius * 2 pi * 0.25 / (65 * 2) / 2^z (77,067 m at level 0, 18.8 m at 12).
double level_error(int z);

// ---- The coverage: the DEMs as one lattice in longitude and latitude --------------------------

// The posts of a lattice too large for memory, read by bands of rows through the DEMs' windows
// and kept in a cache of the most recently used bands within a memory budget (coverage.cpp).
class LatticeBands;

struct GeoLattice {
    double lon0 = 0, lat0 = 0; // degrees (WGS84) of post (0, 0), the south-west one
    double dlon = 0, dlat = 0; // spacing, degrees (> 0)
    int width = 0, height = 0; // posts
    std::vector<float> z;      // width * height heights, metres, row 0 south; NaN: not covered
    bool resampled = false;    // a DEM was warped onto the lattice (its samples are not posts)
    std::int64_t covered = 0;  // posts that hold a height
    // Set when the lattice is read by windows: `z` is then empty and the posts come from the
    // bands, the same heights post for post as the whole lattice would hold.
    std::shared_ptr<LatticeBands> bands;

    double lon(std::int64_t i) const { return lon0 + double(i) * dlon; }
    double lat(std::int64_t j) const { return lat0 + double(j) * dlat; }
    // Height of post (i, j), or NaN outside the lattice or the DEMs.
    float at(std::int64_t i, std::int64_t j) const {
        if (i < 0 || j < 0 || i >= width || j >= height)
            return NAN;
        return bands ? band_post(i, j) : z[std::size_t(j) * std::size_t(width) + std::size_t(i)];
    }
    // Rows of posts that are best read together (a band; the whole lattice when it is held).
    int rows_together() const;
    // Bands made from the DEMs so far (each a read of the DEMs' rows under it; 0 when the lattice
    // is held whole), and the bands the lattice has.
    std::int64_t bands_read() const;
    std::int64_t band_count() const;

  private:
    float band_post(std::int64_t i, std::int64_t j) const;
};

// How much memory a tile set's run may hold, and what that leaves the lattice.
struct CoverageMemory {
    double memory_mb = 0; // the whole run's budget, MiB (0: no bound, the lattice held whole)
    int threads = 1;      // tiles built at once (each holds its own tile's work)
};

// Loads the DEMs (load_heightfield: voids filled, each must be georeferenced) as one lattice. When
// every DEM is in EPSG:4326 on one grid (same spacing, origins a whole number of posts apart, as
// adjacent SRTM tiles), its samples are the posts, unchanged. Otherwise the lattice takes the
// finest DEM's spacing in degrees (a geographic DEM's own grid) and each post's height is the
// bilinear interpolation of the first DEM (in the order given) whose samples surround it, its
// position transformed into that DEM's CRS with PROJ. Throws Error naming the file at fault.
// Within `memory` the lattice is held whole when it fits, else read by windows (DemWindows) into
// bands the tiles read (docs/tiles.md, "Memory").
GeoLattice load_coverage(const std::vector<std::string> &paths, const LoadOptions &options,
                         const CoverageMemory &memory = {});

// The default memory budget of a run: a share of this machine's physical memory, MiB.
double default_memory_mb();

// The default deepest level: the first whose tiles are at most 64 of the lattice's finer spacing
// across (the 65-post heightmap tile CesiumJS's error estimate assumes is then as fine as the
// DEM), at most finest_zoom().
int default_max_zoom(const GeoLattice &lattice);

// Deepest level whose tiles still hold 4 lattice spacings across (a level deeper has no DEM
// samples to mesh).
int finest_zoom(const GeoLattice &lattice);

// ---- One tile --------------------------------------------------------------------------------

struct TileOptions {
    double fill_height = 0.0; // height outside the coverage, metres above the ellipsoid
    bool normals = false;     // append the oct-encoded vertex normals extension (from the DEM)
};

struct TileMesh {
    TileId id;
    std::vector<std::uint16_t> u, v, h;   // quantized vertices (0 .. 32767)
    std::vector<std::uint32_t> triangles; // 3 vertex indices each, counter-clockwise in u/v
    std::vector<std::uint32_t> west, south, east, north; // edge vertices, in CesiumJS's order
    float min_height = 0, max_height = 0;                // the header's height range
    std::vector<std::uint8_t> normals;                   // 2 bytes per vertex, or empty
    // Measured as a decoder reads the tile: over the covered posts inside the tile, the largest
    // of |TIN - sample| and the sample's distance to its triangle as CesiumJS draws it (flat
    // between Earth-centred vertices), and that over level_error(z).
    double max_error = 0.0;
    double error_ratio = 0.0;
    std::int64_t samples = 0;  // covered posts inside the tile (measured)
    int builds = 0;            // meshes made (more than 1: rebuilt tighter after a measure)
    std::int64_t repaired = 0; // posts the repair made vertices in place (in the build kept)
};

// Heights of the posts a tile's surface depends on (those inside it and the next beyond each
// edge), with the fill height where one is not covered: what fixes the tile's height step.
struct HeightRange {
    double lo = 0, hi = 0;
    bool covered = false; // one of those posts holds a DEM height: the tile is written
};
HeightRange tile_height_range(const GeoLattice &lattice, const TileId &tile,
                              const TileOptions &options);

// The height range of any tile of `tile`'s level; the pyramid keeps them per level, a lone build
// computes them. Tile x wraps around the antimeridian; tiles beyond the poles are never asked.
using RangeOf = std::function<HeightRange(const TileId &)>;

// Builds tile `tile`: a pure function of the lattice, the level, the address and the options.
// `range_of` (optional) gives the height ranges of it and its 8 neighbours (computed when empty).
TileMesh build_tile(const GeoLattice &lattice, const TileId &tile, const TileOptions &options,
                    const RangeOf &range_of = {});

// The quantized-mesh-1.0 bytes of a tile (uncompressed), and gzip's compression of any bytes.
std::vector<std::uint8_t> encode_quantized_mesh(const TileMesh &tile);
std::vector<std::uint8_t> gzip_bytes(const std::vector<std::uint8_t> &bytes);

// ---- The pyramid -------------------------------------------------------------------------------

struct PyramidOptions {
    int min_zoom = 0;
    int max_zoom = 0;
    TileOptions tile;
    int threads = 1;
    // Called with (tiles done, tiles in all) as tiles finish, from the calling thread.
    std::function<void(std::int64_t, std::int64_t)> progress;
};

struct LevelStats {
    int z = 0;
    std::int64_t tiles = 0, triangles = 0, vertices = 0, bytes = 0, rebuilt = 0;
    double bound = 0.0, max_error = 0.0, worst_ratio = 0.0;
    // Tiles still over the bound after every rebuild (written as the best build found), and the
    // tile of the worst ratio.
    std::int64_t over_bound = 0;
    TileId worst_tile;
    // Tiles whose kept build the repair changed, and the posts it made vertices in them.
    std::int64_t repaired = 0, repaired_posts = 0;
    // Bands of a lattice read by windows made while the level was built (0 when held whole).
    std::int64_t bands_read = 0;
};

struct PyramidStats {
    std::vector<LevelStats> levels;
    nlohmann::json layer; // the layer.json written
    double ms = 0.0;
};

// Writes DIR/{z}/{x}/{y}.terrain (gzip) for every tile of levels min_zoom..max_zoom whose surface
// depends on a covered post, and DIR/layer.json (its `available` lists exactly those tiles). The
// tiles are staged and moved in at the end: on an error nothing of the run is left in DIR.
PyramidStats write_pyramid(const GeoLattice &lattice, const std::string &dir,
                           const PyramidOptions &options);

// The tiles of level z that write_pyramid writes, as rectangles of TMS addresses (layer.json's
// form: x0..x1 by y0..y1, inclusive); and layer.json for levels 0..max, for callers that build
// tiles themselves.
struct TileRange {
    std::int64_t x0 = 0, x1 = -1, y0 = 0, y1 = -1;
};
std::vector<TileRange> level_tiles(const GeoLattice &lattice, int z, const TileOptions &options);
// available[z]: level z's rectangles (empty for the levels not built).
nlohmann::json layer_json(const GeoLattice &lattice,
                          const std::vector<std::vector<TileRange>> &available, bool normals);

// ---- A share of the pyramid: the build spread over processes (python/tinlod_dask) -------------

// The subtree of tile `root` (its tiles on levels root.z .. max_zoom that write_pyramid writes), or
// with `top`, every tile of the levels min_zoom .. root.z - 1 (those above a cut at level root.z).
struct PyramidPart {
    TileId root;
    bool top = false;
};

// Writes the part's tiles into DIR/{z}/{x}/{y}.terrain, each in place at once (a temporary
// renamed), and no layer.json: the same bytes as write_pyramid's for those tiles (a tile is a pure
// function of the lattice, its level, its address and the options), so parts run anywhere, in any
// order, again after a failure, make write_pyramid's tile set.
PyramidStats write_pyramid_part(const GeoLattice &lattice, const std::string &dir,
                                const PyramidOptions &options, const PyramidPart &part);

// The layer.json write_pyramid writes with `options`, without building a tile; and its text
// written to `path`.
nlohmann::json pyramid_layer(const GeoLattice &lattice, const PyramidOptions &options);
void write_layer(const nlohmann::json &layer, const std::string &path);

} // namespace tinlod
