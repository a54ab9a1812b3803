// The quad-tree store on disk (see store.hpp): written tile-major with a CRC-32 per section and per
// tile, read through a memory map that only the tiles the traversal reaches are paged in from, and
// a cache that drops the least recently used tiles (madvise) beyond its cap.
#include "tinlod/store.hpp"

#include "node_bound.hpp"
#include "tinlod/error.hpp"
#include "tinlod/util.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <thread>

namespace tinlod {

static_assert(std::endian::native == std::endian::little, "the store format is little-endian");
static_assert(sizeof(NodeBound) == 12);

namespace {

constexpr char k_magic[8] = {'T', 'I', 'N', 'L', 'O', 'D', 'Q', 'T'};
constexpr std::size_t k_fixed_header = 128; // bytes before the CRS string
constexpr std::size_t k_dir_entry = 24;     // offset u64, bytes u64, crc u32, pad u32
constexpr std::uint64_t k_page = 4096;

// CRC-32 (IEEE 802.3, as zlib's crc32), slicing by 8 bytes.
using CrcTables = std::array<std::array<std::uint32_t, 256>, 8>;
constexpr CrcTables make_crc_tables() {
    CrcTables t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k)
            c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        t[0][n] = c;
    }
    for (std::uint32_t n = 0; n < 256; ++n)
        for (int k = 1; k < 8; ++k)
            t[k][n] = (t[k - 1][n] >> 8) ^ t[0][t[k - 1][n] & 0xFF];
    return t;
}
constexpr CrcTables k_crc = make_crc_tables();

std::uint32_t crc32(const void *data, std::size_t n) {
    const auto *p = static_cast<const std::uint8_t *>(data);
    std::uint32_t c = 0xFFFFFFFFu;
    for (; n >= 8; n -= 8, p += 8) {
        std::uint32_t lo, hi;
        std::memcpy(&lo, p, 4);
        std::memcpy(&hi, p + 4, 4);
        lo ^= c;
        c = k_crc[7][lo & 0xFF] ^ k_crc[6][(lo >> 8) & 0xFF] ^ k_crc[5][(lo >> 16) & 0xFF] ^
            k_crc[4][lo >> 24] ^ k_crc[3][hi & 0xFF] ^ k_crc[2][(hi >> 8) & 0xFF] ^
            k_crc[1][(hi >> 16) & 0xFF] ^ k_crc[0][hi >> 24];
    }
    for (; n > 0; --n, ++p)
        c = k_crc[0][(c ^ *p) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

std::uint64_t align(std::uint64_t v, std::uint64_t a) { return (v + a - 1) / a * a; }

// Where every node and sample of a layout goes in the store: the tile level, the level of the
// corner elevations, each tile's descendants per level and the byte layout of each tile.
struct StoreGeometry {
    int levels = 0;
    int tile_level = 0;
    int corner_level = 0;
    std::uint32_t tiles_x = 0, tiles_y = 0;
    // Per axis, per level d >= tile_level: first descendant and count of each tile interval, and
    // the tile interval of each node interval.
    struct Axis {
        std::vector<std::vector<std::uint32_t>> first, count, tile_of;
    } ax, ay;
    std::vector<std::uint64_t> tile_bytes;
    std::vector<std::uint32_t> level_offset; // per tile, per level below the tile level (bytes)
    int tile_levels = 0;                     // levels stored inside tiles

    static void make_axis(const AxisSplit &s, int tile_level, Axis &a) {
        const int levels = s.levels();
        a.first.assign(levels, {});
        a.count.assign(levels, {});
        a.tile_of.assign(levels, {});
        const std::uint32_t n = s.count(tile_level);
        for (std::uint32_t t = 0; t < n; ++t) {
            a.first[tile_level].push_back(t);
            a.count[tile_level].push_back(1);
            a.tile_of[tile_level].push_back(t);
        }
        for (int d = tile_level; d + 1 < levels; ++d) {
            a.tile_of[d + 1].resize(s.count(d + 1));
            for (std::uint32_t t = 0; t < n; ++t) {
                const std::uint32_t f = a.first[d][t], last = f + a.count[d][t] - 1;
                const std::uint32_t cf = s.first_child(d, f);
                const std::uint32_t cl = s.first_child(d, last) + (s.length(d, last) >= 2 ? 1 : 0);
                a.first[d + 1].push_back(cf);
                a.count[d + 1].push_back(cl - cf + 1);
                for (std::uint32_t k = cf; k <= cl; ++k)
                    a.tile_of[d + 1][k] = t;
            }
        }
    }

    explicit StoreGeometry(const QuadLayout &lay) {
        levels = lay.levels();
        auto widest = [](const AxisSplit &s, int d) {
            std::uint32_t m = 0;
            for (std::uint32_t k = 0; k < s.count(d); ++k)
                m = std::max(m, s.length(d, k));
            return m;
        };
        while (tile_level + 1 < levels && (widest(lay.x, tile_level) > k_store_tile_cells ||
                                           widest(lay.y, tile_level) > k_store_tile_cells))
            ++tile_level;
        corner_level = std::min(tile_level + 1, levels - 1);
        tiles_x = lay.x.count(tile_level);
        tiles_y = lay.y.count(tile_level);
        make_axis(lay.x, tile_level, ax);
        make_axis(lay.y, tile_level, ay);
        tile_levels = std::max(levels - 2 - tile_level, 0);
        tile_bytes.resize(std::size_t{tiles_x} * tiles_y);
        level_offset.resize(tile_bytes.size() * tile_levels);
        for (std::uint32_t tj = 0; tj < tiles_y; ++tj)
            for (std::uint32_t ti = 0; ti < tiles_x; ++ti) {
                const std::size_t t = std::size_t{tj} * tiles_x + ti;
                std::uint64_t bytes =
                    4ull * (lay.x.length(tile_level, ti) + 1) * (lay.y.length(tile_level, tj) + 1);
                for (int d = tile_level + 1; d < levels - 1; ++d) {
                    level_offset[t * tile_levels + (d - tile_level - 1)] =
                        static_cast<std::uint32_t>(bytes);
                    bytes += 12ull * ax.count[d][ti] * ay.count[d][tj];
                }
                tile_bytes[t] = bytes;
            }
    }

    std::size_t tile_count() const { return tile_bytes.size(); }
    std::uint64_t top_nodes(const QuadLayout &lay) const {
        std::uint64_t n = 0;
        for (int d = 0; d <= std::min(tile_level, levels - 2); ++d)
            n += lay.level_nodes(d);
        return n;
    }
    std::uint64_t corner_count(const QuadLayout &lay) const {
        return std::uint64_t{lay.x.count(corner_level) + 1} * (lay.y.count(corner_level) + 1);
    }
};

struct Header {
    std::int32_t width = 0, height = 0;
    double dx = 1, dy = 1, origin_x = 0, origin_y = 0;
    std::uint32_t levels = 0, tile_level = 0, corner_level = 0, tile_count = 0;
    std::uint64_t dir_offset = 0, top_offset = 0, top_bytes = 0, corner_offset = 0,
                  corner_bytes = 0;
    std::uint32_t top_crc = 0, corner_crc = 0, dir_crc = 0;
    std::string crs;
};

template <class T> void put(std::vector<std::uint8_t> &b, std::size_t at, const T &v) {
    std::memcpy(b.data() + at, &v, sizeof(T));
}
template <class T> T get(const std::uint8_t *p, std::size_t at) {
    T v;
    std::memcpy(&v, p + at, sizeof(T));
    return v;
}

std::vector<std::uint8_t> encode(const Header &h) {
    std::vector<std::uint8_t> b(k_fixed_header + h.crs.size() + 4, 0);
    std::memcpy(b.data(), k_magic, 8);
    put(b, 8, k_store_version);
    put(b, 12, static_cast<std::uint32_t>(b.size()));
    put(b, 16, h.width);
    put(b, 20, h.height);
    put(b, 24, h.dx);
    put(b, 32, h.dy);
    put(b, 40, h.origin_x);
    put(b, 48, h.origin_y);
    put(b, 56, h.levels);
    put(b, 60, h.tile_level);
    put(b, 64, h.corner_level);
    put(b, 68, h.tile_count);
    put(b, 72, h.dir_offset);
    put(b, 80, h.top_offset);
    put(b, 88, h.top_bytes);
    put(b, 96, h.corner_offset);
    put(b, 104, h.corner_bytes);
    put(b, 112, h.top_crc);
    put(b, 116, h.corner_crc);
    put(b, 120, h.dir_crc);
    put(b, 124, static_cast<std::uint32_t>(h.crs.size()));
    std::memcpy(b.data() + k_fixed_header, h.crs.data(), h.crs.size());
    put(b, b.size() - 4, crc32(b.data(), b.size() - 4));
    return b;
}

class File {
  public:
    File(const std::string &path, const std::string &subject) : subject_(subject) {
        f_ = std::fopen(path.c_str(), "wb");
        if (!f_)
            fail();
    }
    ~File() {
        if (f_)
            std::fclose(f_);
    }
    void write(const void *p, std::size_t n) {
        if (n && std::fwrite(p, 1, n, f_) != n)
            fail();
    }
    void pad_to(std::uint64_t offset) {
        static const std::array<std::uint8_t, k_page> zeros{};
        std::uint64_t at = position();
        while (at < offset) {
            const std::size_t n = std::min<std::uint64_t>(offset - at, zeros.size());
            write(zeros.data(), n);
            at += n;
        }
    }
    std::uint64_t position() const { return static_cast<std::uint64_t>(std::ftell(f_)); }
    void seek(std::uint64_t offset) {
        if (std::fseek(f_, static_cast<long>(offset), SEEK_SET) != 0)
            fail();
    }
    void close() {
        const int rc = std::fclose(f_);
        f_ = nullptr;
        if (rc != 0)
            fail();
    }

  private:
    [[noreturn]] void fail() const {
        throw Error(subject_, std::string("cannot write: ") + std::strerror(errno));
    }
    std::FILE *f_ = nullptr;
    std::string subject_;
};

} // namespace

void check_store_writable(const std::string &path) {
    if (is_stream(path))
        throw Error(path, "a store is written with seeks: give a file, not a device or FIFO");
    check_writable({path});
}

namespace {

// A store being written to `file`: the tiles in order, from the first page after the top tree and
// the corner elevations, then those two sections, the directory and the header, whose offsets and
// checksums are known only then. Every byte not written is zero.
class StoreWriter {
  public:
    StoreWriter(const GridFrame &fr, const StoreGeometry &g, const std::string &file,
                const std::string &path)
        : g_(g), f_(file, path), dir_(k_dir_entry * g.tile_count(), 0) {
        h_.width = fr.width;
        h_.height = fr.height;
        h_.dx = fr.dx;
        h_.dy = fr.dy;
        h_.origin_x = fr.origin_x;
        h_.origin_y = fr.origin_y;
        h_.crs = fr.crs;
        h_.levels = static_cast<std::uint32_t>(g.levels);
        h_.tile_level = static_cast<std::uint32_t>(g.tile_level);
        h_.corner_level = static_cast<std::uint32_t>(g.corner_level);
        h_.tile_count = static_cast<std::uint32_t>(g.tile_count());
        const QuadLayout lay(fr.width, fr.height);
        h_.dir_offset = align(encode(h_).size(), 8);
        h_.top_offset = align(h_.dir_offset + k_dir_entry * g.tile_count(), 8);
        h_.top_bytes = g.top_nodes(lay) * sizeof(NodeBound);
        h_.corner_offset = align(h_.top_offset + h_.top_bytes, 8);
        h_.corner_bytes = g.corner_count(lay) * sizeof(float);
        f_.pad_to(h_.corner_offset + h_.corner_bytes);
    }

    // Tile t, the next one.
    void tile(std::size_t t, const std::vector<std::uint8_t> &bytes) {
        assert(bytes.size() == g_.tile_bytes[t]);
        const std::uint64_t offset = align(f_.position(), k_page);
        f_.pad_to(offset);
        f_.write(bytes.data(), bytes.size());
        put(dir_, t * k_dir_entry, offset);
        put(dir_, t * k_dir_entry + 8, std::uint64_t{bytes.size()});
        put(dir_, t * k_dir_entry + 16, crc32(bytes.data(), bytes.size()));
    }

    // The top tree (levels down to the tile level, each row-major) and the corner elevations.
    void finish(const std::vector<NodeBound> &top, const std::vector<float> &corners) {
        assert(top.size() * sizeof(NodeBound) == h_.top_bytes &&
               corners.size() * sizeof(float) == h_.corner_bytes);
        h_.top_crc = crc32(top.data(), h_.top_bytes);
        h_.corner_crc = crc32(corners.data(), h_.corner_bytes);
        h_.dir_crc = crc32(dir_.data(), dir_.size());
        f_.seek(h_.top_offset);
        f_.write(top.data(), h_.top_bytes);
        f_.seek(h_.corner_offset);
        f_.write(corners.data(), h_.corner_bytes);
        f_.seek(0);
        const auto head = encode(h_);
        f_.write(head.data(), head.size());
        f_.pad_to(h_.dir_offset);
        f_.write(dir_.data(), dir_.size());
        f_.close();
    }

  private:
    const StoreGeometry &g_;
    File f_;
    Header h_;
    std::vector<std::uint8_t> dir_;
};

// The column and row of corner (i, j): the bounds of the corner level.
std::uint32_t corner_at(const AxisSplit &s, int level, std::uint32_t k) {
    return k < s.count(level) ? s.lo(level, k) : s.hi(level, s.count(level) - 1);
}

} // namespace

void write_store(const QuadTree &tree, const std::string &path, Progress *progress) {
    check_store_writable(path);
    const QuadLayout &lay = tree.layout();
    const GridFrame &fr = tree.frame();
    const StoreGeometry g(lay);
    std::vector<NodeBound> top;
    top.reserve(g.top_nodes(lay));
    for (int d = 0; d <= std::min(g.tile_level, g.levels - 2); ++d)
        for (std::uint32_t j = 0; j < lay.y.count(d); ++j)
            for (std::uint32_t i = 0; i < lay.x.count(d); ++i)
                top.push_back(tree.bound(d, i, j));
    std::vector<float> corners;
    corners.reserve(g.corner_count(lay));
    for (std::uint32_t j = 0; j <= lay.y.count(g.corner_level); ++j)
        for (std::uint32_t i = 0; i <= lay.x.count(g.corner_level); ++i)
            corners.push_back(tree.elevation(corner_at(lay.x, g.corner_level, i),
                                             corner_at(lay.y, g.corner_level, j)));
    write_atomically(path, [&](const std::string &tmp) {
        StoreWriter out(fr, g, tmp, path);
        std::vector<std::uint8_t> tile;
        std::int64_t samples_done = 0;
        for (std::uint32_t tj = 0; tj < g.tiles_y; ++tj)
            for (std::uint32_t ti = 0; ti < g.tiles_x; ++ti) {
                const std::size_t t = std::size_t{tj} * g.tiles_x + ti;
                tile.assign(g.tile_bytes[t], 0);
                const std::uint32_t x0 = lay.x.lo(g.tile_level, ti),
                                    x1 = lay.x.hi(g.tile_level, ti);
                const std::uint32_t y0 = lay.y.lo(g.tile_level, tj),
                                    y1 = lay.y.hi(g.tile_level, tj);
                std::size_t at = 0;
                for (std::uint32_t r = y0; r <= y1; ++r) {
                    std::memcpy(tile.data() + at,
                                &tree.elevations()[std::size_t{r} * fr.width + x0],
                                4 * (x1 - x0 + 1));
                    at += 4 * (x1 - x0 + 1);
                }
                for (int d = g.tile_level + 1; d < g.levels - 1; ++d)
                    for (std::uint32_t b = 0; b < g.ay.count[d][tj]; ++b)
                        for (std::uint32_t a = 0; a < g.ax.count[d][ti]; ++a) {
                            const NodeBound nb =
                                tree.bound(d, g.ax.first[d][ti] + a, g.ay.first[d][tj] + b);
                            std::memcpy(tile.data() + at, &nb, sizeof nb);
                            at += sizeof nb;
                        }
                assert(at == tile.size());
                out.tile(t, tile);
                samples_done += std::int64_t{x1 - x0} * (y1 - y0);
                if (progress)
                    progress->update(samples_done);
            }
        out.finish(top, corners);
    });
}

namespace {

// fn(lo, hi) over [0, n) split among the threads.
template <class Fn> void split_over_threads(std::uint32_t n, Fn &&fn) {
    const std::uint32_t workers = std::min<std::uint32_t>(std::uint32_t(max_threads()), n);
    std::vector<std::thread> pool;
    for (std::uint32_t t = 1; t < workers; ++t)
        pool.emplace_back(fn, n * t / workers, n * (t + 1) / workers);
    if (workers > 0)
        fn(0u, n / workers);
    for (auto &th : pool)
        th.join();
}

// Tile (ti, tj) of a band of rows: its samples, then the bounds of its descendants level by level
// (each made from its own error and its children's), as write_store lays it out. Returns the tile
// node's own bound with the bound of its children folded in.
NodeBound band_tile(const QuadLayout &lay, const StoreGeometry &g, const GridRows &rows,
                    std::uint32_t ti, std::uint32_t tj, std::vector<std::uint8_t> &tile) {
    const int tl = g.tile_level, levels = g.levels;
    const std::size_t t = std::size_t{tj} * g.tiles_x + ti;
    tile.assign(g.tile_bytes[t], 0);
    const std::uint32_t x0 = lay.x.lo(tl, ti), x1 = lay.x.hi(tl, ti);
    const std::uint32_t y0 = lay.y.lo(tl, tj), y1 = lay.y.hi(tl, tj);
    std::size_t at = 0;
    for (std::uint32_t r = y0; r <= y1; ++r, at += 4 * (x1 - x0 + 1))
        std::memcpy(tile.data() + at, rows.row(r) + x0, 4 * (x1 - x0 + 1));
    // The bounds of level d sit at the tile's offset for it, row-major over its descendants.
    auto slot = [&](int d, std::uint32_t i, std::uint32_t j) {
        return tile.data() + g.level_offset[t * g.tile_levels + (d - tl - 1)] +
               sizeof(NodeBound) * (std::size_t{j - g.ay.first[d][tj]} * g.ax.count[d][ti] +
                                    (i - g.ax.first[d][ti]));
    };
    auto stored = [&](int d) {
        return [&, d](std::uint32_t i, std::uint32_t j) {
            NodeBound b;
            std::memcpy(&b, slot(d, i, j), sizeof b);
            return b;
        };
    };
    for (int d = levels - 2; d > tl; --d) {
        const bool leaf = d + 1 >= levels - 1;
        for (std::uint32_t b = 0; b < g.ay.count[d][tj]; ++b)
            for (std::uint32_t a = 0; a < g.ax.count[d][ti]; ++a) {
                const std::uint32_t i = g.ax.first[d][ti] + a, j = g.ay.first[d][tj] + b;
                const std::uint32_t nx0 = lay.x.lo(d, i), nx1 = lay.x.hi(d, i);
                const std::uint32_t ny0 = lay.y.lo(d, j), ny1 = lay.y.hi(d, j);
                const NodeBound nb =
                    node_bound(lay, d, i, j, own_bound(rows, nx0, nx1, ny0, ny1, ny0, ny1, leaf),
                               stored(d + 1));
                std::memcpy(slot(d, i, j), &nb, sizeof nb);
            }
    }
    if (tl > levels - 2)
        return {};
    return node_bound(lay, tl, ti, tj,
                      own_bound(rows, x0, x1, y0, y1, y0, y1, tl + 1 >= levels - 1),
                      stored(tl + 1));
}

} // namespace

void write_store_by_rows(const GridFrame &fr, const GridRowReader &read, std::int64_t band_bytes,
                         const std::string &path, Progress *progress) {
    check_store_writable(path);
    check_quad_grid(fr.width, fr.height);
    const QuadLayout lay(fr.width, fr.height);
    const StoreGeometry g(lay);
    const int tl = g.tile_level, cl = g.corner_level, levels = g.levels;
    // Bands: runs of whole tile rows, [band[k], band[k + 1]).
    std::vector<std::uint32_t> band{0};
    const std::int64_t row_bytes = 4 * std::int64_t{fr.width};
    for (std::uint32_t tj = 1; tj < g.tiles_y; ++tj)
        if (std::int64_t{lay.y.hi(tl, tj) - lay.y.lo(tl, band.back()) + 1} * row_bytes > band_bytes)
            band.push_back(tj);
    band.push_back(g.tiles_y);
    std::vector<float> corners(g.corner_count(lay));
    const std::uint32_t corners_x = lay.x.count(cl) + 1, corners_y = lay.y.count(cl) + 1;
    std::int64_t rows_done = 0;
    std::vector<float> z;
    auto read_band = [&](std::size_t k) {
        const std::uint32_t r0 = lay.y.lo(tl, band[k]), r1 = lay.y.hi(tl, band[k + 1] - 1);
        z = read(int(r0), int(r1) + 1);
        assert(z.size() == std::size_t{r1 - r0 + 1} * fr.width);
        rows_done += r1 - r0;
        if (progress)
            progress->update(rows_done);
        GridRows rows;
        rows.band = z.data();
        rows.width = fr.width;
        rows.r0 = r0;
        rows.r1 = r1;
        rows.keys = corners.data();
        rows.layout = &lay;
        rows.key_level = cl;
        return rows;
    };
    for (std::size_t k = 0; k + 1 < band.size(); ++k) {
        const GridRows rows = read_band(k);
        for (std::uint32_t j = 0; j < corners_y; ++j) {
            const std::uint32_t r = corner_at(lay.y, cl, j);
            if (r >= rows.r0 && r <= rows.r1)
                for (std::uint32_t i = 0; i < corners_x; ++i)
                    corners[std::size_t{j} * corners_x + i] = rows.row(r)[corner_at(lay.x, cl, i)];
        }
    }

    // The top tree per level; above the tile level, each node's own error as the bands show it.
    const int top_levels = std::min(tl, levels - 2) + 1;
    std::vector<std::vector<NodeBound>> top(std::size_t(std::max(top_levels, 0)));
    std::vector<std::vector<double>> own(static_cast<std::size_t>(tl));
    for (int d = 0; d < top_levels; ++d)
        top[d].resize(lay.level_nodes(d));
    for (int d = 0; d < tl; ++d)
        own[d].assign(lay.level_nodes(d), 0.0);
    write_atomically(path, [&](const std::string &tmp) {
        StoreWriter out(fr, g, tmp, path);
        std::vector<std::vector<std::uint8_t>> tiles(g.tiles_x);
        for (std::size_t k = 0; k + 1 < band.size(); ++k) {
            const GridRows rows = read_band(k);
            for (std::uint32_t tj = band[k]; tj < band[k + 1]; ++tj) {
                split_over_threads(g.tiles_x, [&](std::uint32_t a, std::uint32_t b) {
                    for (std::uint32_t ti = a; ti < b; ++ti) {
                        const NodeBound nb = band_tile(lay, g, rows, ti, tj, tiles[ti]);
                        if (tl < top_levels)
                            top[tl][std::size_t{tj} * g.tiles_x + ti] = nb;
                    }
                });
                for (std::uint32_t ti = 0; ti < g.tiles_x; ++ti)
                    out.tile(std::size_t{tj} * g.tiles_x + ti, tiles[ti]);
            }
            // Levels above the tiles: their nodes' own errors over the band's rows.
            for (int d = 0; d < tl; ++d) {
                const std::uint32_t nx = lay.x.count(d);
                // The nodes with a cell in the band; one that meets it in a single row (its
                // first or its last) has that row in the band before or after as well.
                const std::uint32_t j0 = lay.y.interval_of(d, rows.r0);
                const std::uint32_t j1 = lay.y.interval_of(d, rows.r1 - 1);
                split_over_threads(nx, [&](std::uint32_t a, std::uint32_t b) {
                    for (std::uint32_t j = j0; j <= j1; ++j)
                        for (std::uint32_t i = a; i < b; ++i) {
                            double &e = own[d][std::size_t{j} * nx + i];
                            e = std::max(e, own_bound(rows, lay.x.lo(d, i), lay.x.hi(d, i),
                                                      lay.y.lo(d, j), lay.y.hi(d, j), rows.r0,
                                                      rows.r1, false)
                                                .error);
                        }
                });
            }
        }
        for (int d = tl - 1; d >= 0; --d)
            for (std::uint32_t j = 0; j < lay.y.count(d); ++j)
                for (std::uint32_t i = 0; i < lay.x.count(d); ++i) {
                    OwnBound o;
                    o.error = own[d][std::size_t{j} * lay.x.count(d) + i];
                    top[d][std::size_t{j} * lay.x.count(d) + i] =
                        node_bound(lay, d, i, j, o, [&](std::uint32_t ci, std::uint32_t cj) {
                            return top[d + 1][std::size_t{cj} * lay.x.count(d + 1) + ci];
                        });
                }
        std::vector<NodeBound> flat;
        flat.reserve(g.top_nodes(lay));
        for (const auto &level : top)
            flat.insert(flat.end(), level.begin(), level.end());
        out.finish(flat, corners);
    });
}
bool is_store_file(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    char magic[8] = {};
    return in.read(magic, 8) && std::memcmp(magic, k_magic, 8) == 0;
}

// ---------------------------------------------------------------------------------------------
// Reading

struct TileStore::Impl {
    std::string path;
    int fd = -1;
    const std::uint8_t *base = nullptr;
    std::size_t size = 0;
    QuadLayout lay;
    GridFrame frame;
    std::unique_ptr<StoreGeometry> g;
    struct Tile {
        std::uint64_t offset = 0, bytes = 0;
        std::uint32_t crc = 0;
        std::uint32_t stamp = 0; // retrieval that last used it
        bool resident = false;   // verified and kept
    };
    std::vector<Tile> tiles;
    std::vector<const NodeBound *> top; // per level down to the tile level
    const float *corners = nullptr;
    std::uint32_t retrieval = 0;
    std::uint64_t resident_bytes = 0, cap_bytes = 0;
    // tile_samples' cache: tiles' samples copied out of the file (read, not mapped: dropping a
    // mapped tile's pages cost about 0.3 ms of system time a tile on a loaded machine), by slot.
    struct Slot {
        std::uint32_t tile = 0;
        std::uint64_t stamp = 0;
        std::vector<float> z;
    };
    std::vector<Slot> slots;
    std::vector<std::uint32_t> free_slots;
    std::vector<std::int32_t> slot_of; // per tile: its slot, or -1
    std::vector<std::uint8_t> scratch; // one tile's bytes, to verify
    std::uint64_t sample_bytes = 0, sample_stamp = 0;
    std::int64_t resident_count = 0;
    StoreStats last, total;

    [[noreturn]] void bad(const std::string &reason) const { throw Error(path, reason); }

    ~Impl() {
        if (base)
            ::munmap(const_cast<std::uint8_t *>(base), size);
        if (fd >= 0)
            ::close(fd);
    }

    void open(const std::string &p, const StoreOptions &options) {
        path = p;
        cap_bytes = static_cast<std::uint64_t>(std::max(options.cache_mb, 0.0) * 1024 * 1024);
        fd = ::open(p.c_str(), O_RDONLY);
        if (fd < 0)
            bad(std::string("cannot open: ") + std::strerror(errno));
        struct stat sb;
        if (::fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode))
            bad("not a regular file");
        size = static_cast<std::size_t>(sb.st_size);
        if (size < 8)
            bad("not a tinlod quad-tree store (file too short)");
        void *m = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
        if (m == MAP_FAILED)
            bad(std::string("cannot map: ") + std::strerror(errno));
        base = static_cast<const std::uint8_t *>(m);
        if (std::memcmp(base, k_magic, 8) != 0)
            bad("not a tinlod quad-tree store (bad magic)");
        if (size < k_fixed_header + 4)
            bad("truncated store: the header is incomplete");
        const auto version = get<std::uint32_t>(base, 8);
        if (version != k_store_version)
            bad("store version " + std::to_string(version) + " is not supported (expected " +
                std::to_string(k_store_version) + ")");
        const auto header_bytes = get<std::uint32_t>(base, 12);
        const auto crs_len = get<std::uint32_t>(base, 124);
        if (header_bytes != k_fixed_header + std::uint64_t{crs_len} + 4 || header_bytes > size)
            bad("corrupt or truncated store header");
        if (get<std::uint32_t>(base, header_bytes - 4) != crc32(base, header_bytes - 4))
            bad("corrupt store header (checksum mismatch)");
        Header h;
        h.width = get<std::int32_t>(base, 16);
        h.height = get<std::int32_t>(base, 20);
        h.dx = get<double>(base, 24);
        h.dy = get<double>(base, 32);
        h.origin_x = get<double>(base, 40);
        h.origin_y = get<double>(base, 48);
        h.levels = get<std::uint32_t>(base, 56);
        h.tile_level = get<std::uint32_t>(base, 60);
        h.corner_level = get<std::uint32_t>(base, 64);
        h.tile_count = get<std::uint32_t>(base, 68);
        h.dir_offset = get<std::uint64_t>(base, 72);
        h.top_offset = get<std::uint64_t>(base, 80);
        h.top_bytes = get<std::uint64_t>(base, 88);
        h.corner_offset = get<std::uint64_t>(base, 96);
        h.corner_bytes = get<std::uint64_t>(base, 104);
        h.top_crc = get<std::uint32_t>(base, 112);
        h.corner_crc = get<std::uint32_t>(base, 116);
        h.dir_crc = get<std::uint32_t>(base, 120);
        h.crs.assign(reinterpret_cast<const char *>(base) + k_fixed_header, crs_len);
        if (h.width < 2 || h.height < 2 || std::int64_t{h.width} * h.height > k_max_raster_samples)
            bad("corrupt store header (grid size " + std::to_string(h.width) + "x" +
                std::to_string(h.height) + ")");
        if (!(std::isfinite(h.dx) && h.dx > 0 && std::isfinite(h.dy) && h.dy > 0))
            bad("corrupt store header (cell size)");
        // Every sample is in some tile: a file smaller than the samples is cut short.
        if (4 * std::uint64_t(h.width) * std::uint64_t(h.height) > size)
            bad("truncated store: " + std::to_string(size) + " bytes cannot hold " +
                std::to_string(h.width) + "x" + std::to_string(h.height) + " samples");
        lay = QuadLayout(h.width, h.height);
        frame = {h.width, h.height, h.dx, h.dy, h.origin_x, h.origin_y, h.crs};
        g = std::make_unique<StoreGeometry>(lay);
        if (h.levels != std::uint32_t(g->levels) || h.tile_level != std::uint32_t(g->tile_level) ||
            h.corner_level != std::uint32_t(g->corner_level) || h.tile_count != g->tile_count())
            bad("corrupt store header (tree shape does not match the grid size)");
        auto section = [&](std::uint64_t offset, std::uint64_t bytes, const char *what) {
            if (offset % 8 != 0 || offset > size || bytes > size - offset)
                bad(std::string("truncated store: the ") + what +
                    " lies beyond the end of the file");
        };
        section(h.dir_offset, k_dir_entry * g->tile_count(), "tile directory");
        section(h.top_offset, h.top_bytes, "top tree");
        section(h.corner_offset, h.corner_bytes, "corner elevations");
        if (h.top_bytes != g->top_nodes(lay) * sizeof(NodeBound) ||
            h.corner_bytes != g->corner_count(lay) * sizeof(float))
            bad("corrupt store header (section sizes)");
        if (crc32(base + h.dir_offset, k_dir_entry * g->tile_count()) != h.dir_crc)
            bad("corrupt tile directory (checksum mismatch)");
        if (crc32(base + h.top_offset, h.top_bytes) != h.top_crc)
            bad("corrupt top tree (checksum mismatch)");
        if (crc32(base + h.corner_offset, h.corner_bytes) != h.corner_crc)
            bad("corrupt corner elevations (checksum mismatch)");
        const auto *top_nodes = reinterpret_cast<const NodeBound *>(base + h.top_offset);
        for (int d = 0; d <= std::min(g->tile_level, g->levels - 2); ++d) {
            top.push_back(top_nodes);
            top_nodes += lay.level_nodes(d);
        }
        corners = reinterpret_cast<const float *>(base + h.corner_offset);
        tiles.resize(g->tile_count());
        for (std::size_t t = 0; t < tiles.size(); ++t) {
            const std::uint8_t *e = base + h.dir_offset + t * k_dir_entry;
            Tile &tile = tiles[t];
            tile.offset = get<std::uint64_t>(e, 0);
            tile.bytes = get<std::uint64_t>(e, 8);
            tile.crc = get<std::uint32_t>(e, 16);
            if (tile.bytes != g->tile_bytes[t] || tile.offset % k_page != 0)
                bad("corrupt tile directory (tile " + std::to_string(t) + ")");
            if (tile.offset > size || tile.bytes > size - tile.offset)
                bad("truncated store: tile " + std::to_string(t) + " of " +
                    std::to_string(tiles.size()) + " lies beyond the end of the file (" +
                    std::to_string(size) + " bytes)");
        }
    }

    const std::uint8_t *tile_data(std::size_t t) {
        Tile &tile = tiles[t];
        if (!tile.resident) {
            if (crc32(base + tile.offset, tile.bytes) != tile.crc)
                bad("corrupt tile " + std::to_string(t) + " (checksum mismatch)");
            tile.resident = true;
            resident_bytes += tile.bytes;
            ++resident_count;
            ++last.tiles_read;
            last.bytes_read += static_cast<std::int64_t>(tile.bytes);
        }
        tile.stamp = retrieval;
        return base + tile.offset;
    }

    std::size_t tile_of(int d, std::uint32_t i, std::uint32_t j, std::uint32_t &ti,
                        std::uint32_t &tj) const {
        ti = g->ax.tile_of[d][i];
        tj = g->ay.tile_of[d][j];
        return std::size_t{tj} * g->tiles_x + ti;
    }

    NodeBound bound(int d, std::uint32_t i, std::uint32_t j) {
        if (d <= g->tile_level)
            return top[d][std::size_t{j} * lay.x.count(d) + i];
        std::uint32_t ti, tj;
        const std::size_t t = tile_of(d, i, j, ti, tj);
        const std::uint8_t *data = tile_data(t);
        const std::uint32_t li = i - g->ax.first[d][ti], lj = j - g->ay.first[d][tj];
        NodeBound b;
        std::memcpy(&b,
                    data + g->level_offset[t * g->tile_levels + (d - g->tile_level - 1)] +
                        sizeof(NodeBound) * (std::size_t{lj} * g->ax.count[d][ti] + li),
                    sizeof b);
        return b;
    }

    float vertex_z(int d, std::uint32_t i, std::uint32_t j, std::uint32_t c, std::uint32_t r) {
        if (d <= g->tile_level) {
            const int cl = g->corner_level;
            const std::uint32_t ci = lay.x.bound_index(cl, c), ri = lay.y.bound_index(cl, r);
            return corners[std::size_t{ri} * (lay.x.count(cl) + 1) + ci];
        }
        std::uint32_t ti, tj;
        const std::size_t t = tile_of(d, i, j, ti, tj);
        const std::uint8_t *data = tile_data(t);
        const std::uint32_t x0 = lay.x.lo(g->tile_level, ti), y0 = lay.y.lo(g->tile_level, tj);
        const std::uint32_t w = lay.x.length(g->tile_level, ti) + 1;
        float z;
        std::memcpy(&z, data + 4 * (std::size_t{r - y0} * w + (c - x0)), sizeof z);
        return z;
    }

    // Gives tile's pages back to the kernel: they are read from the file again when touched.
    void drop_pages(const Tile &tile) const {
        ::madvise(const_cast<std::uint8_t *>(base) + tile.offset, align(tile.bytes, k_page),
                  MADV_DONTNEED);
    }

    // Drops the least recently used tiles until at most `target` bytes stay (at the end of a
    // retrieval, so the tiles of the view in progress stay mapped while it runs); their pages
    // leave memory and are read and verified again if a later view needs them.
    void evict(std::uint64_t target) {
        if (resident_bytes <= target)
            return;
        std::vector<std::size_t> order;
        for (std::size_t t = 0; t < tiles.size(); ++t)
            if (tiles[t].resident)
                order.push_back(t);
        std::sort(order.begin(), order.end(),
                  [&](std::size_t a, std::size_t b) { return tiles[a].stamp < tiles[b].stamp; });
        for (std::size_t t : order) {
            if (resident_bytes <= target)
                break;
            Tile &tile = tiles[t];
            drop_pages(tile);
            tile.resident = false;
            resident_bytes -= tile.bytes;
            --resident_count;
            ++last.tiles_evicted;
        }
    }
};

TileStore::TileStore(const std::string &path, const StoreOptions &options)
    : impl_(std::make_unique<Impl>()) {
    impl_->open(path, options);
}

TileStore::~TileStore() = default;

const QuadLayout &TileStore::layout() const { return impl_->lay; }
const GridFrame &TileStore::frame() const { return impl_->frame; }
NodeBound TileStore::bound(int d, std::uint32_t i, std::uint32_t j) {
    return impl_->bound(d, i, j);
}
float TileStore::vertex_z(int d, std::uint32_t i, std::uint32_t j, std::uint32_t c,
                          std::uint32_t r) {
    return impl_->vertex_z(d, i, j, c, r);
}

void TileStore::begin_retrieval() {
    ++impl_->retrieval;
    impl_->last = {};
}

void TileStore::end_retrieval() {
    impl_->evict(impl_->cap_bytes);
    impl_->total.tiles_read += impl_->last.tiles_read;
    impl_->total.bytes_read += impl_->last.bytes_read;
    impl_->total.tiles_evicted += impl_->last.tiles_evicted;
}

TileSamples TileStore::tile_samples(std::uint32_t i, std::uint32_t j) {
    Impl &s = *impl_;
    const int tl = s.g->tile_level;
    const std::uint32_t t = j * s.g->tiles_x + i;
    const std::uint32_t x0 = s.lay.x.lo(tl, i), y0 = s.lay.y.lo(tl, j), x1 = s.lay.x.hi(tl, i),
                        y1 = s.lay.y.hi(tl, j);
    if (s.slot_of.empty())
        s.slot_of.assign(s.tiles.size(), -1);
    if (s.slot_of[t] < 0) {
        // The mapped tiles of the last retrieval leave first: the cap holds both caches.
        s.evict(0);
        const std::size_t n = std::size_t{x1 - x0 + 1} * (y1 - y0 + 1);
        if (s.free_slots.empty() && !s.slots.empty() && s.sample_bytes + 4 * n > s.cap_bytes) {
            // The least recently used quarter goes at once: each eviction sorts the slots.
            std::vector<std::uint32_t> order(s.slots.size());
            for (std::uint32_t k = 0; k < order.size(); ++k)
                order[k] = k;
            std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
                return s.slots[a].stamp < s.slots[b].stamp;
            });
            for (std::size_t k = 0; k < std::max<std::size_t>(1, order.size() / 4); ++k) {
                Impl::Slot &old = s.slots[order[k]];
                s.slot_of[old.tile] = -1;
                s.free_slots.push_back(order[k]);
            }
        }
        std::uint32_t k;
        if (s.free_slots.empty()) {
            k = std::uint32_t(s.slots.size());
            s.slots.emplace_back();
            s.sample_bytes += 4 * n;
        } else {
            k = s.free_slots.back();
            s.free_slots.pop_back();
            s.sample_bytes += 4 * n;
            s.sample_bytes -= 4 * s.slots[k].z.size();
        }
        const Impl::Tile &tile = s.tiles[t];
        s.scratch.resize(tile.bytes);
        std::size_t got = 0;
        while (got < tile.bytes) {
            const ssize_t r =
                ::pread(s.fd, s.scratch.data() + got, tile.bytes - got, off_t(tile.offset + got));
            if (r <= 0)
                s.bad("cannot read tile " + std::to_string(t) + ": " +
                      (r < 0 ? std::strerror(errno) : "end of file"));
            got += std::size_t(r);
        }
        if (crc32(s.scratch.data(), tile.bytes) != tile.crc)
            s.bad("corrupt tile " + std::to_string(t) + " (checksum mismatch)");
        Impl::Slot &slot = s.slots[k];
        slot.tile = t;
        slot.z.resize(n);
        std::memcpy(slot.z.data(), s.scratch.data(), 4 * n);
        s.slot_of[t] = std::int32_t(k);
        ++s.last.tiles_read;
        s.last.bytes_read += std::int64_t(tile.bytes);
    }
    Impl::Slot &slot = s.slots[std::size_t(s.slot_of[t])];
    slot.stamp = ++s.sample_stamp;
    return {x0, y0, x1, y1, slot.z.data()};
}

int TileStore::tile_level() const { return impl_->g->tile_level; }
std::int64_t TileStore::tile_count() const {
    return static_cast<std::int64_t>(impl_->tiles.size());
}
std::int64_t TileStore::resident_tiles() const { return impl_->resident_count; }
std::int64_t TileStore::resident_bytes() const {
    return static_cast<std::int64_t>(impl_->resident_bytes);
}
std::int64_t TileStore::file_bytes() const { return static_cast<std::int64_t>(impl_->size); }
const StoreStats &TileStore::last_stats() const { return impl_->last; }
const StoreStats &TileStore::total_stats() const { return impl_->total; }

Heightfield TileStore::heightfield() const {
    const Impl &s = *impl_;
    Heightfield hf;
    hf.width = s.frame.width;
    hf.height = s.frame.height;
    hf.dx = s.frame.dx;
    hf.dy = s.frame.dy;
    hf.origin_x = s.frame.origin_x;
    hf.origin_y = s.frame.origin_y;
    hf.crs = s.frame.crs;
    hf.z.resize(static_cast<std::size_t>(hf.size()));
    const int tl = s.g->tile_level;
    for (std::uint32_t tj = 0; tj < s.g->tiles_y; ++tj)
        for (std::uint32_t ti = 0; ti < s.g->tiles_x; ++ti) {
            const std::size_t t = std::size_t{tj} * s.g->tiles_x + ti;
            const auto &tile = s.tiles[t];
            if (crc32(s.base + tile.offset, tile.bytes) != tile.crc)
                s.bad("corrupt tile " + std::to_string(t) + " (checksum mismatch)");
            const std::uint32_t x0 = s.lay.x.lo(tl, ti), x1 = s.lay.x.hi(tl, ti);
            const std::uint32_t y0 = s.lay.y.lo(tl, tj), y1 = s.lay.y.hi(tl, tj);
            const std::uint8_t *p = s.base + tile.offset;
            for (std::uint32_t r = y0; r <= y1; ++r, p += 4 * (x1 - x0 + 1))
                std::memcpy(&hf.z[std::size_t{r} * hf.width + x0], p, 4 * (x1 - x0 + 1));
            // Its pages leave memory again unless the cache holds the tile: the heights returned
            // are a copy, and the file's pages stayed resident beside them.
            if (!tile.resident)
                s.drop_pages(tile);
        }
    return hf;
}

} // namespace tinlod
