// Grid TINs' lattice scans (lattice_scan.hpp).
#include "erase/lattice_scan.hpp"

namespace tinlod::erase {

std::uint32_t grid_width(const Mesh &m) {
    const std::size_t n = m.n_vertices();
    if (n < 4 || n > std::size_t(std::numeric_limits<std::int32_t>::max()))
        return 0;
    const Mesh::Point *p = m.points();
    std::size_t w = 1;
    while (w < n && p[w][1] == p[0][1])
        ++w;
    if (w < 2 || w == n || n % w != 0)
        return 0;
    const auto monotone = [](float a, float b, float c) { return (a < b) == (b < c) && b != c; };
    for (std::size_t c = 2; c < w; ++c)
        if (!monotone(p[c - 2][0], p[c - 1][0], p[c][0]))
            return 0;
    for (std::size_t r = 2 * w; r < n; r += w)
        if (!monotone(p[r - 2 * w][1], p[r - w][1], p[r][1]))
            return 0;
    if (p[0][0] == p[1][0] || p[0][1] == p[w][1])
        return 0;
    for (std::size_t r = 0; r < n; r += w)
        for (std::size_t c = 0; c < w; ++c)
            if (p[r + c][0] != p[c][0] || p[r + c][1] != p[r][1])
                return 0;
    return std::uint32_t(w);
}

void build_tile_z(std::vector<float> &tile_z, const Input &input) {
    const std::int64_t w = input.grid_w, rows = std::int64_t(input.nodes) / w;
    const std::int64_t columns = tile_columns(input);
    tile_z.assign(std::size_t(2 * columns * ((rows - 1) / k_band_rows + 1)), 0.0f);
    const Samples g = samples(input);
    for (std::int64_t r = 0; r < rows; ++r) {
        float *band = tile_z.data() + 2 * (r / k_band_rows) * columns;
        for (std::int64_t c0 = 0; c0 < w; c0 += k_tile_cols) {
            float lo = INFINITY, hi = -INFINITY;
            for (std::int64_t c = c0; c < std::min(w, c0 + k_tile_cols); ++c) {
                lo = std::min(lo, g.at(c, r)[2]);
                hi = std::max(hi, g.at(c, r)[2]);
            }
            float *tile = band + 2 * (c0 / k_tile_cols);
            if (r % k_band_rows == 0) {
                tile[0] = lo;
                tile[1] = hi;
            } else {
                tile[0] = std::min(tile[0], lo);
                tile[1] = std::max(tile[1], hi);
            }
        }
    }
}

std::pair<float, std::int32_t> face_worst(const EraserState &s, std::uint32_t a, std::uint32_t b,
                                          std::uint32_t c, const TriangleFrame &f,
                                          const glm::dvec3 &pa, const glm::dvec3 &pb,
                                          const glm::dvec3 &pc) {
    const TrianglePlane plane = f.plane;
    const double margin = plane.margin_over(pa, pb, pc);
    double maxdev = 0.0;
    std::int32_t worst = -1;
    const auto visit = [&](std::uint32_t u, const Mesh::Point &p) {
        const double dev = plane.deviation(p[0], p[1], p[2], margin);
        if (dev > maxdev) {
            maxdev = dev;
            worst = std::int32_t(u);
        }
        return true;
    };
    // The face's samples but its corners in row order, as scan_lattice's rows give them: a small
    // face over its box, a larger one by spans carried from row to row (visit_inside): most faces
    // of a TIN from greedy insertion hold a few samples, and scan_lattice's spans cost two
    // divisions a row and edge (docs/decisions/038-simplify-speed-7-floor.md).
    const std::int64_t w = s.input.grid_w;
    const std::int64_t x[3] = {a % w, b % w, c % w}, y[3] = {a / w, b / w, c / w};
    const Samples g = samples(s.input);
    visit_inside(x, y, [&](std::int64_t col, std::int64_t row) {
        return visit(std::uint32_t(row * w + col), g.at(col, row));
    });
    return {float_up(maxdev), worst};
}

} // namespace tinlod::erase
