// Grid TINs: scans of the samples a face swallowed, row by row from the lattice.
// A TIN whose nodes are all the samples of a w x h lattice, node r * w + c at column c of row r
// (grid_tin's layout): the nodes a face swallowed are exactly the samples inside it other than its
// corners, so they are scanned row by row from the lattice instead of kept in lists. A scan reads
// the points in memory order and needs no locate, and a face that changes moves no node.
#pragma once

#include "erase/state.hpp"
#include "lattice_triangle.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace tinlod::erase {

// The lattice's width when the mesh is such a TIN (every point on the lattice its first row and
// column span, in order), else 0.
std::uint32_t grid_width(const Mesh &m);

// Visits the nodes a face with corner nodes a, b, c of a grid TIN swallowed, band by band of
// k_band_rows rows: band(lo, hi) gets the xy box of the band's samples and returns a value
// visit(u, p, value) is given for each sample u (point p) of the band, or a negative value to skip
// the band. visit returns false to stop the scan; then so does scan_lattice, and so does band_end,
// called after each band's samples.
template <class Band, class Visit, class BandEnd = bool (*)()>
inline bool scan_lattice(
    const EraserState &s, std::uint32_t a, std::uint32_t b, std::uint32_t c, const Band &band,
    const Visit &visit, const BandEnd &band_end = [] { return true; }) {
    const std::int64_t w = s.input.grid_w;
    const LatticeTriangle t(s.input.grid_w, a, b, c);
    const Samples g = samples(s.input);
    // Left uninitialised, as a std::pair would be zeroed on every call
    // (docs/decisions/009-prefetching.md): each band writes the spans of its rows before it reads
    // them.
    struct Span {
        std::int64_t first, second;
    };
    std::array<Span, k_band_rows> spans;
    for (std::int64_t y0 = t.first_row; y0 <= t.last_row; y0 += k_band_rows) {
        const std::int64_t y1 = std::min(y0 + k_band_rows - 1, t.last_row);
        std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = -1;
        for (std::int64_t y = y0; y <= y1; ++y) {
            const auto [first, last] = t.span(y);
            spans[y - y0] = {first, last};
            if (spans[y - y0].first <= spans[y - y0].second) {
                lo = std::min(lo, spans[y - y0].first);
                hi = std::max(hi, spans[y - y0].second);
            }
        }
        if (lo > hi)
            continue;
        const double xa = g.x(lo), xb = g.x(hi), ya = g.y(y0), yb = g.y(y1);
        const double value = band(glm::dvec2(std::min(xa, xb), std::min(ya, yb)),
                                  glm::dvec2(std::max(xa, xb), std::max(ya, yb)));
        if (value < 0.0)
            continue;
        // The band's rows lie a lattice row apart in memory, too far for the hardware to guess:
        // asking for all of them before the first is read overlaps their cache misses
        // (docs/decisions/009-prefetching.md).
        for (std::int64_t y = y0; y <= y1; ++y)
            g.prefetch(y, spans[y - y0].first, spans[y - y0].second);
        for (std::int64_t y = y0; y <= y1; ++y)
            for (std::int64_t x = spans[y - y0].first; x <= spans[y - y0].second; ++x) {
                const std::uint32_t u = std::uint32_t(y * w + x);
                if (u != a && u != b && u != c && !visit(u, g.at(x, y), value))
                    return false;
            }
        if (!band_end())
            return false;
    }
    return true;
}

// The lattice's tiles: tile (r / k_band_rows, c / k_tile_cols) holds sample (c, r).
inline std::int64_t tile_columns(const Input &input) {
    return (std::int64_t(input.grid_w) - 1) / k_tile_cols + 1;
}

// The least and largest height of each tile of a grid TIN's lattice (one pass over the samples),
// into tile_z: per band of tiles, per tile, the two.
void build_tile_z(std::vector<float> &tile_z, const Input &input);

// The tiling of face (a, b, c): its rows, and the lattice tiles over its box, bands from row0 and
// columns from x0 (multiples of the tile's sides).
struct Tiling {
    LatticeTriangle t;
    std::int64_t row0, x0, columns; // tile columns: [x0 + k * k_tile_cols, ... + k_tile_cols)
};

inline Tiling tiling(const EraserState &s, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const std::int64_t w = s.input.grid_w;
    const std::int64_t x0 = std::min({a % w, b % w, c % w}) / k_tile_cols * k_tile_cols,
                       x1 = std::max({a % w, b % w, c % w});
    const LatticeTriangle t(s.input.grid_w, a, b, c);
    return {t, t.first_row / k_band_rows * k_band_rows, x0, (x1 - x0) / k_tile_cols + 1};
}

// Visits the samples of face (a, b, c) tile by tile: tile(lo, hi, bound) gets the xy box of a
// tile's samples and the bound on their deviation, and returns the value visit(u, q, dev, value)
// is given for each of them (q its point, dev = deviation(q)), or a negative value to skip the
// tile. A tile visited lowers its bound in `dev` to its samples' largest deviation.
template <class Tile, class Deviation, class Visit>
inline void scan_tiles(const EraserState &s, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                       std::vector<float> &dev, const Tile &tile, const Deviation &deviation,
                       const Visit &visit) {
    const std::int64_t w = s.input.grid_w;
    const Tiling g = tiling(s, a, b, c);
    const Samples lattice = samples(s.input);
    std::array<std::pair<std::int64_t, std::int64_t>, k_band_rows> spans;
    for (std::int64_t y0 = g.row0; y0 <= g.t.last_row; y0 += k_band_rows) {
        const std::int64_t ya = std::max(y0, g.t.first_row),
                           y1 = std::min(y0 + k_band_rows - 1, g.t.last_row);
        const std::int64_t band = (y0 - g.row0) / k_band_rows;
        std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = -1;
        for (std::int64_t y = ya; y <= y1; ++y) {
            spans[y - y0] = g.t.span(y);
            if (spans[y - y0].first <= spans[y - y0].second) {
                lo = std::min(lo, spans[y - y0].first);
                hi = std::max(hi, spans[y - y0].second);
            }
        }
        if (lo > hi)
            continue;
        for (std::int64_t k = (lo - g.x0) / k_tile_cols; k <= (hi - g.x0) / k_tile_cols; ++k) {
            float &bound = dev[std::size_t(band * g.columns + k)];
            const std::int64_t c0 = std::max(lo, g.x0 + k * k_tile_cols),
                               c1 = std::min(hi, g.x0 + (k + 1) * k_tile_cols - 1);
            const double xa = lattice.x(c0), xb = lattice.x(c1), yl = lattice.y(ya),
                         yh = lattice.y(y1);
            const double value =
                tile(glm::dvec2(std::min(xa, xb), std::min(yl, yh)),
                     glm::dvec2(std::max(xa, xb), std::max(yl, yh)), double(bound));
            if (value < 0.0)
                continue;
            double most = 0.0;
            for (std::int64_t y = ya; y <= y1; ++y)
                for (std::int64_t x = std::max(c0, spans[y - y0].first),
                                  end = std::min(c1, spans[y - y0].second);
                     x <= end; ++x) {
                    const std::uint32_t u = std::uint32_t(y * w + x);
                    if (u == a || u == b || u == c)
                        continue;
                    const glm::dvec3 q = to_glm(lattice.at(x, y));
                    const double d = deviation(q);
                    most = std::max(most, d);
                    visit(u, q, d, value);
                }
            bound = std::min(bound, float_up(most));
        }
    }
}

// Whether the face of tiling g is worth tiles: it holds more than about k_tiled_samples samples
// (half its box).
inline bool worth_tiles(const Tiling &g) {
    const std::int64_t rows = g.t.last_row - g.t.first_row + 1;
    return rows * g.columns * k_tile_cols / 2 > k_tiled_samples;
}

// The tile bounds of the face of tiling g (corners a, b, c, its plane), per band and tile column:
// a tile's bound is the largest distance from the height range of its lattice tile (tile_z, see
// build_tile_z) to the face's plane over its box, widened like a deviation (the plane's margin at
// its farthest corner, and a hair for the rounding of these sums); no sample is read.
inline std::vector<float> tile_bounds(const EraserState &s, const std::vector<float> &tile_z,
                                      const Tiling &g, std::uint32_t a, std::uint32_t b,
                                      std::uint32_t c, const TrianglePlane &plane) {
    const std::int64_t w = s.input.grid_w, columns = tile_columns(s.input);
    const std::int64_t x_lo = std::min({a % w, b % w, c % w}),
                       x_hi = std::max({a % w, b % w, c % w});
    const Samples lattice = samples(s.input);
    const std::int64_t bands = (g.t.last_row - g.row0) / k_band_rows + 1;
    std::vector<float> dev(std::size_t(bands * g.columns));
    for (std::int64_t j = 0; j < bands; ++j) {
        const std::int64_t r0 = std::max(g.row0 + j * k_band_rows, g.t.first_row),
                           r1 = std::min(g.row0 + (j + 1) * k_band_rows - 1, g.t.last_row);
        const double y0 = lattice.y(r0), y1 = lattice.y(r1);
        for (std::int64_t k = 0; k < g.columns; ++k) {
            const std::int64_t c0 = std::max(g.x0 + k * k_tile_cols, x_lo),
                               c1 = std::min(g.x0 + (k + 1) * k_tile_cols - 1, x_hi);
            const double x0 = lattice.x(c0), x1 = lattice.x(c1);
            const float *z = tile_z.data() +
                             2 * ((g.row0 / k_band_rows + j) * columns + (g.x0 / k_tile_cols + k));
            const double p[4] = {plane.height(x0, y0), plane.height(x1, y0), plane.height(x0, y1),
                                 plane.height(x1, y1)};
            const double pl = std::min({p[0], p[1], p[2], p[3]}),
                         ph = std::max({p[0], p[1], p[2], p[3]});
            const double far = std::max({std::abs(x0), std::abs(x1), std::abs(y0), std::abs(y1)});
            const double most = std::max({double(z[1]) - pl, ph - double(z[0]), 0.0});
            dev[std::size_t(j * g.columns + k)] =
                float_up(most + plane.margin(far) +
                         1e-9 * (std::abs(pl) + std::abs(ph) + std::abs(double(z[0])) +
                                 std::abs(double(z[1])) + 1.0));
        }
    }
    return dev;
}

// The samples strictly inside a grid TIN's hole (the node itself among them), by Pick's theorem:
// the ring's area in lattice cells less half the samples on it, plus one.
inline std::int64_t lattice_inside(const EraserState &s, const Hole &h) {
    const std::int64_t w = s.input.grid_w;
    std::int64_t twice = 0, on_ring = 0;
    for (int i = 0; i < h.n; ++i) {
        const std::int64_t a = node_of(s, h.r[i]), b = node_of(s, h.r[(i + 1) % h.n]);
        twice += (a % w) * (b / w) - (b % w) * (a / w);
        on_ring += std::gcd(std::abs(b % w - a % w), std::abs(b / w - a / w));
    }
    return (std::abs(twice) - on_ring) / 2 + 1;
}

// The largest deviation (rounded up) of the samples a grid TIN's face with corner nodes a, b, c
// (points pa, pb, pc, frame f) swallowed, and the sample that has it (-1 when none deviates).
std::pair<float, std::int32_t> face_worst(const EraserState &s, std::uint32_t a, std::uint32_t b,
                                          std::uint32_t c, const TriangleFrame &f,
                                          const glm::dvec3 &pa, const glm::dvec3 &pb,
                                          const glm::dvec3 &pc);

} // namespace tinlod::erase
