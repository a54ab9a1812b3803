// The quad-tree store on disk (.tlq): the paper's quad-tree "database", read partially, tile by
// tile, as the traversal reaches it, through a memory map and a size-capped cache.
//
// Layout (little-endian): a header (magic "TINLODQT", version, grid size, spacing, origin, CRS, the
// level of the tiles, section offsets, checksums), a tile directory (offset, bytes, CRC-32 per
// tile), the bounds of every node down to the tile level, the elevations at the corners of the
// level below it, then the tiles, each page aligned. A tile is one node of the tile level: its
// samples (inclusive rectangle, row-major) followed by the bounds of all its descendant nodes,
// level by level.
#pragma once

#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tinlod {

class Progress;

inline constexpr std::uint32_t k_store_version = 1;
inline constexpr int k_store_tile_cells = 64; // tiles are the first level whose nodes span <= this

// Writes `tree` as a store at `path` through write_atomically. Throws Error naming the path when it
// cannot be written. `progress` (optional) advances by samples written, out of width * height.
void write_store(const QuadTree &tree, const std::string &path, Progress *progress = nullptr);

// Rows [r0, r1) of a grid (row 0 south, as a Heightfield's), every column, row-major: how
// write_store_by_rows reads a DEM (DemWindows::rows).
using GridRowReader = std::function<std::vector<float>(int r0, int r1)>;

// Writes the store of the grid `frame` describes, the same bytes as write_store of its QuadTree,
// reading its rows through `read` a band at a time and never holding them all: bands of whole
// tile rows, each of at most band_bytes of heights (one tile row however small that is). The
// grid is read twice: first for the corner elevations, which the node bounds of the levels above
// the tiles are made from, then for the tiles and every bound. `progress` (optional) advances by
// rows read, out of 2 * (height - 1).
void write_store_by_rows(const GridFrame &frame, const GridRowReader &read, std::int64_t band_bytes,
                         const std::string &path, Progress *progress = nullptr);

// Throws Error when `path` cannot take a store: check_writable's checks, and a store is written
// with seeks, so not to a stream (is_stream: a device, a FIFO, the standard output).
void check_store_writable(const std::string &path);

// True when the file starts with the store magic (it may still be corrupt).
bool is_store_file(const std::string &path);

struct StoreOptions {
    double cache_mb = 256.0; // tiles kept resident between retrievals, MiB; the tiles of the view
                             // in progress stay resident until it ends
};

// The samples of one tile: an inclusive rectangle of the grid, row-major.
struct TileSamples {
    std::uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    const float *z = nullptr; // (x1 - x0 + 1) a row

    float at(std::uint32_t c, std::uint32_t r) const {
        return z[std::size_t{r - y0} * (x1 - x0 + 1) + (c - x0)];
    }
};

struct StoreStats {
    std::int64_t tiles_read = 0; // tiles loaded and verified (cache misses)
    std::int64_t bytes_read = 0; // their bytes
    std::int64_t tiles_evicted = 0;
};

// A store opened for retrieval. Opening checks the header, the directory and the top sections
// (sizes, checksums) and throws Error naming the file on any mismatch; a tile is verified against
// its checksum when it is first read, and a mismatch throws Error naming the tile.
class TileStore final : public NodeSource {
  public:
    explicit TileStore(const std::string &path, const StoreOptions &options = {});
    ~TileStore() override;
    TileStore(const TileStore &) = delete;
    TileStore &operator=(const TileStore &) = delete;

    const QuadLayout &layout() const override;
    const GridFrame &frame() const override;
    NodeBound bound(int d, std::uint32_t i, std::uint32_t j) override;
    float vertex_z(int d, std::uint32_t i, std::uint32_t j, std::uint32_t c,
                   std::uint32_t r) override;
    void begin_retrieval() override;
    void end_retrieval() override;

    // The samples of node (tile_level(), i, j), for reads outside a retrieval (erase_store):
    // read and verified on a miss into a cache of samples, which with the mapped tiles holds
    // cache_mb (the mapped ones leave at the first miss; past the cap the least recently used
    // quarter of the cached tiles goes). Valid until the next call.
    TileSamples tile_samples(std::uint32_t i, std::uint32_t j);

    int tile_level() const;
    std::int64_t tile_count() const;
    std::int64_t resident_tiles() const;
    std::int64_t resident_bytes() const; // bytes of the resident tiles
    std::int64_t file_bytes() const;
    const StoreStats &last_stats() const;  // of the last retrieval
    const StoreStats &total_stats() const; // since opening
    // Every sample, each tile verified (for exhaustive checks); does not touch the cache or stats.
    Heightfield heightfield() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace tinlod
