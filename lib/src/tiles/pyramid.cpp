// The tile pyramid: which tiles each level writes, layer.json, and the build over threads
// (tiles.hpp: write_pyramid).
#include "post_range.hpp"

#include "tinlod/error.hpp"
#include "tinlod/tiles.hpp"
#include "tinlod/util.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <thread>

namespace tinlod {

namespace fs = std::filesystem;

namespace {

// The height ranges of a level's tiles near the coverage (those written and their neighbours).
struct LevelRanges {
    int z = 0;
    std::map<std::pair<std::int64_t, std::int64_t>, HeightRange> ranges;
    std::vector<TileId> written; // row by row from the south-west
};

// Tiles of level z whose surface may depend on a post: those over the lattice and one post
// beyond, clipped to the level's tiles.
void candidate_span(const GeoLattice &g, int z, std::int64_t &x0, std::int64_t &x1,
                    std::int64_t &y0, std::int64_t &y1) {
    const double size = 180.0 / std::ldexp(1.0, z);
    const std::int64_t nx = std::int64_t(2) << z, ny = std::int64_t(1) << z;
    x0 = std::clamp<std::int64_t>(std::int64_t(std::floor((g.lon(-1) + 180.0) / size)), 0, nx - 1);
    x1 = std::clamp<std::int64_t>(std::int64_t(std::floor((g.lon(g.width) + 180.0) / size)), 0,
                                  nx - 1);
    y0 = std::clamp<std::int64_t>(std::int64_t(std::floor((g.lat(-1) + 90.0) / size)), 0, ny - 1);
    y1 = std::clamp<std::int64_t>(std::int64_t(std::floor((g.lat(g.height) + 90.0) / size)), 0,
                                  ny - 1);
}

// Narrows a level's span of tiles to `clip`'s (empty, x1 < x0 or y1 < y0, when they miss).
void clip_span(const TileRange &clip, std::int64_t &x0, std::int64_t &x1, std::int64_t &y0,
               std::int64_t &y1) {
    x0 = std::max(x0, clip.x0), x1 = std::min(x1, clip.x1);
    y0 = std::max(y0, clip.y0), y1 = std::min(y1, clip.y1);
}

// `range` (optional) gives a tile's height range, else it is read from the lattice; `clip`
// (optional) keeps the tiles written to those addresses (a part of the pyramid).
LevelRanges level_ranges(const GeoLattice &g, int z, const TileOptions &options,
                         const RangeOf &range = {}, const TileRange *clip = nullptr) {
    LevelRanges lr;
    lr.z = z;
    std::int64_t x0, x1, y0, y1;
    candidate_span(g, z, x0, x1, y0, y1);
    if (clip)
        clip_span(*clip, x0, x1, y0, y1);
    const std::int64_t nx = std::int64_t(2) << z, ny = std::int64_t(1) << z;
    for (std::int64_t y = std::max<std::int64_t>(0, y0 - 1); y <= std::min(ny - 1, y1 + 1); ++y)
        for (std::int64_t dx = x0 - 1; dx <= x1 + 1; ++dx) {
            const std::int64_t x = (dx % nx + nx) % nx;
            const TileId id{z, x, y};
            const HeightRange r = range ? range(id) : tile_height_range(g, id, options);
            lr.ranges[{x, y}] = r;
            if (r.covered && y >= y0 && y <= y1 && dx >= x0 && dx <= x1)
                lr.written.push_back(id);
        }
    // CesiumJS draws nothing under a level-0 tile it lacks (no parent to upsample it from): level
    // 0 is written whole, a tile over no DEM flat at the fill height.
    if (z == 0)
        lr.written = {{0, 0, 0}, {0, 1, 0}};
    if (clip)
        std::erase_if(lr.written, [clip](const TileId &t) {
            return t.x < clip->x0 || t.x > clip->x1 || t.y < clip->y0 || t.y > clip->y1;
        });
    return lr;
}

// The height ranges of levels up to `last`, the lattice read once: a tile of `last` reads its
// posts, a coarser one joins its children's (post_range.hpp). Not thread-safe.
class PyramidRanges {
  public:
    PyramidRanges(const GeoLattice &g, int last, const TileOptions &options)
        : g_(g), last_(last), options_(options), levels_(std::size_t(last + 1)) {}

    HeightRange operator()(const TileId &t) { return tiles::with_fill(posts(t), options_); }

  private:
    tiles::PostRange posts(const TileId &t) {
        auto &level = levels_[std::size_t(t.z)];
        if (const auto it = level.find({t.x, t.y}); it != level.end())
            return it->second;
        tiles::PostRange r;
        if (t.z >= last_ || !tiles::tile_meets_lattice(g_, t)) {
            r = tiles::tile_post_range(g_, t);
        } else {
            for (int k = 0; k < 4; ++k)
                r.add(posts({t.z + 1, 2 * t.x + (k & 1), 2 * t.y + (k >> 1)}));
        }
        level[{t.x, t.y}] = r;
        return r;
    }

    const GeoLattice &g_;
    int last_;
    TileOptions options_;
    std::vector<std::map<std::pair<std::int64_t, std::int64_t>, tiles::PostRange>> levels_;
};

// Rows of tiles as layer.json's rectangles: each row's runs, merged with the row above when they
// span the same columns.
std::vector<TileRange> rectangles(const std::vector<TileId> &tiles) {
    std::map<std::int64_t, std::vector<std::int64_t>> rows;
    for (const TileId &t : tiles)
        rows[t.y].push_back(t.x);
    std::vector<TileRange> out, open;
    std::int64_t last_y = INT64_MIN;
    for (auto &[y, xs] : rows) {
        std::sort(xs.begin(), xs.end());
        std::vector<TileRange> runs;
        for (const std::int64_t x : xs)
            if (!runs.empty() && runs.back().x1 + 1 == x)
                runs.back().x1 = x;
            else
                runs.push_back({x, x, y, y});
        std::vector<TileRange> next;
        for (TileRange &r : runs) {
            const auto same = std::find_if(open.begin(), open.end(), [&](const TileRange &o) {
                return o.x0 == r.x0 && o.x1 == r.x1 && o.y1 + 1 == y && last_y + 1 == y;
            });
            if (same != open.end()) {
                r.y0 = same->y0;
                open.erase(same);
            }
            next.push_back(r);
        }
        out.insert(out.end(), open.begin(), open.end());
        open = std::move(next);
        last_y = y;
    }
    out.insert(out.end(), open.begin(), open.end());
    std::sort(out.begin(), out.end(), [](const TileRange &a, const TileRange &b) {
        return std::tie(a.y0, a.x0) < std::tie(b.y0, b.x0);
    });
    return out;
}

// Writes a tile to `path`; an error names `shown`, its place in the tile set.
void write_bytes(const std::string &path, const std::vector<std::uint8_t> &bytes,
                 const std::string &shown) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char *>(bytes.data()), std::streamsize(bytes.size()));
    out.close();
    if (!out)
        throw Error(shown, "cannot write the tile");
}

// Builds a level's tiles on options.threads threads and hands each one's gzip bytes to
// write(name, bytes), name its place in the tile set (z/x/y.terrain); reports progress from the
// calling thread (done: tiles finished before this level, total: in the whole run).
LevelStats
build_level(const GeoLattice &g, const LevelRanges &lr, const PyramidOptions &options,
            std::int64_t done, std::int64_t total,
            const std::function<void(const fs::path &, const std::vector<std::uint8_t> &)> &write) {
    LevelStats ls;
    ls.z = lr.z;
    ls.bound = level_error(lr.z);
    const RangeOf range_of = [&lr, &g, &options](const TileId &t) {
        const auto it = lr.ranges.find({t.x, t.y});
        return it != lr.ranges.end() ? it->second : tile_height_range(g, t, options.tile);
    };
    const std::int64_t bands_before = g.bands_read();
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    std::atomic<std::int64_t> finished{0};
    std::mutex lock;
    std::exception_ptr failure;
    const auto work = [&] {
        while (!stop) {
            const std::size_t k = next++;
            if (k >= lr.written.size())
                return;
            const TileId &t = lr.written[k];
            try {
                const TileMesh m = build_tile(g, t, options.tile, range_of);
                const std::vector<std::uint8_t> bytes = gzip_bytes(encode_quantized_mesh(m));
                write(fs::path(std::to_string(t.z)) / std::to_string(t.x) /
                          (std::to_string(t.y) + ".terrain"),
                      bytes);
                const std::lock_guard<std::mutex> guard(lock);
                ++ls.tiles;
                ls.triangles += std::int64_t(m.triangles.size() / 3);
                ls.vertices += std::int64_t(m.u.size());
                ls.bytes += std::int64_t(bytes.size());
                ls.rebuilt += m.builds > 1 ? 1 : 0;
                ls.max_error = std::max(ls.max_error, m.max_error);
                ls.over_bound += m.error_ratio > 1.0 ? 1 : 0;
                ls.repaired += m.repaired > 0 ? 1 : 0;
                ls.repaired_posts += m.repaired;
                if (m.error_ratio > ls.worst_ratio || ls.tiles == 1) {
                    ls.worst_ratio = m.error_ratio;
                    ls.worst_tile = t;
                }
            } catch (...) {
                const std::lock_guard<std::mutex> guard(lock);
                if (!failure)
                    failure = std::current_exception();
                stop = true;
            }
            ++finished;
        }
    };
    // Workers build the tiles; the calling thread reports progress, and an interrupt it takes
    // there stops them before it unwinds.
    std::vector<std::thread> workers;
    const int threads = std::max(1, std::min<int>(options.threads, int(lr.written.size())));
    for (int k = 0; k < threads; ++k)
        workers.emplace_back(work);
    std::exception_ptr interrupted;
    for (;;) {
        try {
            if (options.progress)
                options.progress(done + finished, total);
            check_interrupt();
        } catch (...) {
            interrupted = std::current_exception();
            stop = true;
        }
        if (stop || finished >= std::int64_t(lr.written.size()))
            break;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    for (std::thread &w : workers)
        w.join();
    if (interrupted)
        std::rethrow_exception(interrupted);
    if (failure)
        std::rethrow_exception(failure);
    ls.bands_read = g.bands_read() - bands_before;
    return ls;
}

} // namespace

std::vector<TileRange> level_tiles(const GeoLattice &lattice, int z, const TileOptions &options) {
    return rectangles(level_ranges(lattice, z, options).written);
}

nlohmann::json layer_json(const GeoLattice &g, const std::vector<std::vector<TileRange>> &available,
                          bool normals) {
    nlohmann::json levels = nlohmann::json::array();
    for (const auto &level : available) {
        nlohmann::json rects = nlohmann::json::array();
        for (const TileRange &r : level)
            rects.push_back({{"startX", r.x0}, {"startY", r.y0}, {"endX", r.x1}, {"endY", r.y1}});
        levels.push_back(rects);
    }
    const auto clamp = [](double x, double lo, double hi) { return std::clamp(x, lo, hi); };
    nlohmann::json layer = {
        {"tilejson", "2.1.0"},
        {"name", "tinlod"},
        {"description", "Terrain TIN tiles made by tinlod, each within CesiumJS's geometric "
                        "error for its level at every DEM sample"},
        {"version", "1.0.0"},
        {"format", "quantized-mesh-1.0"},
        {"attribution", ""},
        {"scheme", "tms"},
        {"tiles", {"{z}/{x}/{y}.terrain?v={version}"}},
        {"projection", "EPSG:4326"},
        {"bounds",
         {clamp(g.lon(0), -180, 180), clamp(g.lat(0), -90, 90),
          clamp(g.lon(g.width - 1), -180, 180), clamp(g.lat(g.height - 1), -90, 90)}},
        {"minzoom", 0},
        {"maxzoom", int(available.size()) - 1},
        {"available", levels},
        {"extensions",
         normals ? nlohmann::json::array({"octvertexnormals"}) : nlohmann::json::array()}};
    return layer;
}

PyramidStats write_pyramid(const GeoLattice &g, const std::string &dir,
                           const PyramidOptions &options) {
    const Stopwatch clock;
    PyramidStats stats;
    std::vector<LevelRanges> levels;
    std::int64_t total = 0;
    // Deepest level first, so that each coarser one joins ranges already read.
    PyramidRanges ranges(g, options.max_zoom, options.tile);
    for (int z = options.max_zoom; z >= options.min_zoom; --z) {
        levels.insert(levels.begin(), level_ranges(g, z, options.tile, std::ref(ranges)));
        total += std::int64_t(levels.front().written.size());
    }
    StagedFolder stage(dir);
    std::vector<std::vector<TileRange>> available(std::size_t(options.max_zoom + 1));
    std::int64_t done = 0;
    for (const LevelRanges &lr : levels) {
        available[std::size_t(lr.z)] = rectangles(lr.written);
        stage.write(std::to_string(lr.z), [&](const std::string &path) {
            for (const TileId &t : lr.written)
                fs::create_directories(fs::path(path) / std::to_string(t.x));
            stats.levels.push_back(
                build_level(g, lr, options, done, total,
                            [&](const fs::path &name, const std::vector<std::uint8_t> &bytes) {
                                write_bytes((fs::path(path).parent_path() / name).string(), bytes,
                                            (fs::path(dir) / name).string());
                            }));
        });
        done += std::int64_t(lr.written.size());
    }
    stats.layer = layer_json(g, available, options.tile.normals);
    stage.write("layer.json", [&](const std::string &path) { write_layer(stats.layer, path); });
    // Levels written before are replaced whole.
    std::error_code ec;
    for (const LevelRanges &lr : levels)
        fs::remove_all(fs::path(dir) / std::to_string(lr.z), ec);
    stage.commit();
    stats.ms = clock.ms();
    return stats;
}

// ---- A share of the pyramid (a build spread over processes) -----------------------------------

// The levels a part holds and, on each, its tiles' addresses: a subtree's span shifted down a
// level at a time, or every tile of the levels above the cut.
static std::vector<LevelRanges> part_levels(const GeoLattice &g, const PyramidOptions &options,
                                            const PyramidPart &part) {
    std::vector<LevelRanges> levels;
    if (part.top) {
        for (int z = options.min_zoom; z < part.root.z; ++z)
            levels.push_back(level_ranges(g, z, options.tile));
        return levels;
    }
    for (int z = part.root.z; z <= options.max_zoom; ++z) {
        const int d = z - part.root.z;
        const TileRange span{part.root.x << d, ((part.root.x + 1) << d) - 1, part.root.y << d,
                             ((part.root.y + 1) << d) - 1};
        levels.push_back(level_ranges(g, z, options.tile, {}, &span));
    }
    return levels;
}

PyramidStats write_pyramid_part(const GeoLattice &g, const std::string &dir,
                                const PyramidOptions &options, const PyramidPart &part) {
    const Stopwatch clock;
    PyramidStats stats;
    const std::vector<LevelRanges> levels = part_levels(g, options, part);
    std::int64_t total = 0, done = 0;
    for (const LevelRanges &lr : levels)
        total += std::int64_t(lr.written.size());
    for (const LevelRanges &lr : levels) {
        for (const TileId &t : lr.written)
            fs::create_directories(fs::path(dir) / std::to_string(t.z) / std::to_string(t.x));
        // Each tile in place at once (a temporary renamed): a part run again, or killed, leaves
        // whole tiles only, and other parts write beside it.
        stats.levels.push_back(
            build_level(g, lr, options, done, total,
                        [&](const fs::path &name, const std::vector<std::uint8_t> &bytes) {
                            const std::string path = (fs::path(dir) / name).string();
                            write_atomically(path, [&](const std::string &tmp) {
                                write_bytes(tmp, bytes, path);
                            });
                        }));
        done += std::int64_t(lr.written.size());
    }
    stats.ms = clock.ms();
    return stats;
}

nlohmann::json pyramid_layer(const GeoLattice &g, const PyramidOptions &options) {
    std::vector<std::vector<TileRange>> available(std::size_t(options.max_zoom + 1));
    for (int z = options.min_zoom; z <= options.max_zoom; ++z)
        available[std::size_t(z)] = level_tiles(g, z, options.tile);
    return layer_json(g, available, options.tile.normals);
}

void write_layer(const nlohmann::json &layer, const std::string &path) {
    std::ofstream out(path);
    out << layer.dump(2) << "\n";
    out.close();
    if (!out)
        throw Error(path, "cannot write layer.json");
}

} // namespace tinlod
