// Paper steps 3-4: the hole a node leaves, re-triangulated in its projection plane by ear
// clipping, with the paper's erasing-ability test of an ear. The ring (paper step 3) is the node's
// spokes in the order the half-edges circulate, counter-clockwise (gather_ring, hole_geometry.hpp).
// clip_ears is what the erase runs (min_max_triangulation too, on a grid TIN's vertical holes);
// ring_orientation, is_erasable_ear and triangulate_ring give the tests and the benchmarks the same
// ears on a polygon.
#pragma once

#include "tinlod/decimate.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace tinlod::erase {

// One triangle of a re-triangulated ring: three ring indices, counter-clockwise.
struct RingTriangle {
    std::uint8_t a, b, c;
};

enum class RingOrientation { ccw, cw, degenerate };

// Orientation of the closed polygon `ring` by the sign of its area.
RingOrientation ring_orientation(std::span<const glm::dvec2> ring);

// The paper's erasing-ability test for the ear at ring index i of the counter-clockwise polygon
// `ring`: the corner (i-1, i, i+1) is strictly convex and no other ring node lies in the closed
// triangle.
bool is_erasable_ear(std::span<const glm::dvec2> ring, int i);

// Ear clipping of a simple counter-clockwise polygon (at most k_max_ring nodes), as clip_ears.
// Returns ring.size() - 2 triangles, or an empty vector when the ring cannot be triangulated
// without a fold-over.
std::vector<RingTriangle> triangulate_ring(std::span<const glm::dvec2> ring);

// Twice the signed area of the triangle abc: positive when it is counter-clockwise.
inline double orient(const glm::dvec2 &a, const glm::dvec2 &b, const glm::dvec2 &c) {
    return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

// Ear clipping of the counter-clockwise polygon q[0..n); writes n-2 triangles to `out` and returns
// their count, or -1 when no erasable ear is left before the end. Each step clips the best shaped
// Delaunay ear, or the best shaped ear when none is Delaunay; the circumcircle test runs only on
// ears in order of quality until one passes (a Delaunay ear stays Delaunay as nodes leave).
int clip_ears(const glm::dvec2 *q, int n, RingTriangle *out);

// Whether the chord from q[i] to q[j] of the counter-clockwise polygon q[0..n) is one of its sides
// or a diagonal: inside the polygon near both ends, and meeting no side but at its ends (the flip
// pass's test of a triangle that some triangulation of the hole can hold).
bool is_ring_chord(const glm::dvec2 *q, int n, int i, int j);

// The triangulation of the counter-clockwise polygon q[0..n) (3 <= n <= k_max_ring) whose most
// costly triangle costs least, among those whose every triangle costs at most `limit`, by dynamic
// programming over the polygon's chords: every triangulation of a polygon splits it by some
// triangle on its side (0, n - 1) into two smaller ones. A triangle (i, j, k) on two sides or
// chords (i, j) and (j, k), counter-clockwise with no other ring node in it, lies inside the
// polygon, so (i, k) is a chord too (a side crossing it would end in the triangle, or cross
// (i, j) or (j, k)): the sub-polygons need no chord test of their own
// (docs/decisions/025-simplify-speed-2.md). cost(a, b, c, stop) gives the cost
// of the triangle (a, b, c) (a < b < c, counter-clockwise, no other ring node in it), exactly up to
// `stop`, beyond it any value > stop; it is asked once per such triangle at most. Writes n - 2
// triangles to `out` and returns their count, or -1 when no triangulation keeps within the limit.
template <class Cost>
int min_max_triangulation(const glm::dvec2 *q, int n, double limit, const Cost &cost,
                          RingTriangle *out) {
    if (n < 3 || n > k_max_ring)
        return -1;
    // best[i][k]: the least largest cost over the triangulations of the sub-polygon q[i..k]
    // (closed by the chord k -> i), infinite when none is within the limit; apex[i][k]: the third
    // corner of its triangle on that chord.
    std::array<std::array<double, k_max_ring>, k_max_ring> best;
    std::array<std::array<std::uint8_t, k_max_ring>, k_max_ring> apex;
    const auto empty = [&](int a, int b, int c) {
        for (int j = 0; j < n; ++j)
            if (j != a && j != b && j != c && orient(q[a], q[b], q[j]) >= 0.0 &&
                orient(q[b], q[c], q[j]) >= 0.0 && orient(q[c], q[a], q[j]) >= 0.0)
                return false;
        return true;
    };
    for (int i = 0; i + 1 < n; ++i)
        best[i][i + 1] = 0.0;
    for (int len = 2; len < n; ++len)
        for (int i = 0; i + len < n; ++i) {
            const int k = i + len;
            double &b = best[i][k];
            b = std::numeric_limits<double>::infinity();
            for (int j = i + 1; j < k; ++j) {
                const double sub = std::max(best[i][j], best[j][k]);
                const double stop = std::min(limit, b);
                if (!(sub <= stop) || !(orient(q[i], q[j], q[k]) > 0.0))
                    continue;
                if (!empty(i, j, k))
                    continue;
                const double c = std::max(sub, cost(i, j, k, stop));
                if (c <= limit && c < b) {
                    b = c;
                    apex[i][k] = std::uint8_t(j);
                }
            }
        }
    if (!(best[0][n - 1] <= limit) || std::isinf(best[0][n - 1]))
        return -1;
    int count = 0, top = 0;
    std::array<std::array<std::uint8_t, 2>, k_max_ring> stack;
    stack[top++] = {0, std::uint8_t(n - 1)};
    while (top > 0) {
        const auto [i, k] = stack[--top];
        if (k - i < 2)
            continue;
        const std::uint8_t j = apex[i][k];
        out[count++] = {i, j, k};
        stack[top++] = {i, j};
        stack[top++] = {j, k};
    }
    return count;
}

} // namespace tinlod::erase
