// Pieces the benchmarks share: larger terrains made from real ones (Catmull-Rom enlargement plus
// value-noise detail), crops, and the xy fold-over count of a TIN.
//
// Enlargement: bicubic (Catmull-Rom) resampling of a real DEM to (cells*s + 1) samples per side
// over the same ground (cells s times smaller), plus fractal detail at the new scale: 4 octaves of
// value noise, the finest 4 new cells wide with amplitude 0.5 m, each coarser octave twice as wide
// and 1.6x as strong (about 8 m of detail in all, well below the real relief).
#pragma once

#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tinlod::bench {

inline float catmull_rom(float p0, float p1, float p2, float p3, float t) {
    return p1 + 0.5f * t *
                    (p2 - p0 + t * (2 * p0 - 5 * p1 + 4 * p2 - p3 + t * (3 * (p1 - p2) + p3 - p0)));
}

inline float hash01(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
    std::uint32_t h = x * 374761393u + y * 668265263u + seed * 2246822519u;
    h = (h ^ (h >> 13)) * 1274126177u;
    return float((h ^ (h >> 16)) & 0xFFFFFF) / float(0xFFFFFF) - 0.5f;
}

inline float value_noise(double u, double v, std::uint32_t seed) {
    const auto x = std::uint32_t(u), y = std::uint32_t(v);
    const float fx = float(u - x), fy = float(v - y);
    const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
    const float a = hash01(x, y, seed), b = hash01(x + 1, y, seed), c = hash01(x, y + 1, seed),
                d = hash01(x + 1, y + 1, seed);
    return a + (b - a) * sx + (c - a) * sy + (a - b - c + d) * sx * sy;
}

// `src` enlarged by `scale` (see the file comment): round((width-1)*scale)+1 samples per side.
inline Heightfield enlarge(const Heightfield &src, double scale) {
    Heightfield out;
    const int cells = int(std::lround((src.width - 1) * scale));
    out.width = out.height = cells + 1;
    out.dx = src.dx * (src.width - 1) / cells;
    out.dy = src.dy * (src.height - 1) / cells;
    out.crs = src.crs;
    out.z.resize(std::size_t(out.width) * out.height);
    auto at = [&](int c, int r) {
        return src.at(std::clamp(c, 0, src.width - 1), std::clamp(r, 0, src.height - 1));
    };
    for (int r = 0; r < out.height; ++r) {
        const double v = double(r) * (src.height - 1) / cells;
        const int r0 = std::min(int(v), src.height - 2);
        const float tv = float(v - r0);
        for (int c = 0; c < out.width; ++c) {
            const double u = double(c) * (src.width - 1) / cells;
            const int c0 = std::min(int(u), src.width - 2);
            const float tu = float(u - c0);
            float rows[4];
            for (int k = 0; k < 4; ++k)
                rows[k] = catmull_rom(at(c0 - 1, r0 - 1 + k), at(c0, r0 - 1 + k),
                                      at(c0 + 1, r0 - 1 + k), at(c0 + 2, r0 - 1 + k), tu);
            float detail = 0.0f, amp = 0.5f;
            double period = 4.0;
            for (int o = 0; o < 4; ++o, amp *= 1.6f, period *= 2)
                detail += amp * value_noise(c / period, r / period, std::uint32_t(o));
            out.z[std::size_t(r) * out.width + c] =
                catmull_rom(rows[0], rows[1], rows[2], rows[3], tv) + detail;
        }
    }
    return out;
}

// The width x height samples of `hf` starting at column c0, row r0 (clipped to the grid); the
// origin moves with the crop.
inline Heightfield crop(const Heightfield &hf, int width, int height, int c0 = 0, int r0 = 0) {
    Heightfield c = hf;
    c.width = std::min(width, hf.width - c0);
    c.height = std::min(height, hf.height - r0);
    c.origin_x = hf.origin_x + c0 * hf.dx;
    c.origin_y = hf.origin_y + r0 * hf.dy;
    c.z.resize(std::size_t(c.width) * c.height);
    for (int r = 0; r < c.height; ++r)
        for (int col = 0; col < c.width; ++col)
            c.at(col, r) = hf.at(c0 + col, r0 + r);
    c.void_mask.clear();
    return c;
}

// Twice the signed xy area of a triangle (positive: counter-clockwise seen from above).
inline double xy_area2(const Mesh::Point &a, const Mesh::Point &b, const Mesh::Point &c) {
    return double(b[0] - a[0]) * (c[1] - a[1]) - double(c[0] - a[0]) * (b[1] - a[1]);
}

// Live faces of a TIN whose xy area is <= 0 (fold-overs and slivers of zero area).
inline std::int64_t folded_faces(const Mesh &mesh) {
    std::int64_t n = 0;
    for (auto f : mesh.faces()) {
        if (mesh.status(f).deleted())
            continue;
        Mesh::Point p[3];
        int i = 0;
        for (auto v : f.vertices())
            p[i++] = mesh.point(v);
        n += xy_area2(p[0], p[1], p[2]) <= 0.0;
    }
    return n;
}

} // namespace tinlod::bench
