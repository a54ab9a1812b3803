// Ear clipping of a hole's ring, and the ring functions of the tests (ring_triangulation.hpp).
#include "erase/ring_triangulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tinlod::erase {

namespace {

bool in_closed_triangle(const glm::dvec2 &a, const glm::dvec2 &b, const glm::dvec2 &c,
                        const glm::dvec2 &p) {
    return orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0;
}

// Positive when d lies strictly inside the circumcircle of the counter-clockwise triangle abc.
double in_circle(const glm::dvec2 &a, const glm::dvec2 &b, const glm::dvec2 &c,
                 const glm::dvec2 &d) {
    const double adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y;
    const double cdx = c.x - d.x, cdy = c.y - d.y;
    return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) -
           (bdx * bdx + bdy * bdy) * (adx * cdy - cdx * ady) +
           (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}

// The paper's erasing-ability test of the ear (a, b, c) of the remaining polygon linked by `next`:
// strictly convex at b and no other remaining node in the closed triangle. Returns the ear's shape
// quality in (0, 1] (2*sqrt(3)*area2 / sum of squared edges), or -1 when it is not erasable.
double ear_quality(const glm::dvec2 *q, const std::uint8_t *next, int a, int b, int c) {
    const double area2 = orient(q[a], q[b], q[c]);
    if (area2 <= 0.0)
        return -1.0;
    for (int j = next[c]; j != a; j = next[j])
        if (in_closed_triangle(q[a], q[b], q[c], q[j]))
            return -1.0;
    const auto sq = [](const glm::dvec2 &v) { return v.x * v.x + v.y * v.y; };
    const double edges = sq(q[b] - q[a]) + sq(q[c] - q[b]) + sq(q[a] - q[c]);
    return 2.0 * std::sqrt(3.0) * area2 / edges;
}

// Whether the circumcircle of the ear (a, b, c) holds no other remaining node (a Delaunay ear).
bool is_delaunay_ear(const glm::dvec2 *q, const std::uint8_t *next, int a, int b, int c) {
    for (int j = next[c]; j != a; j = next[j])
        if (in_circle(q[a], q[b], q[c], q[j]) > 0.0)
            return false;
    return true;
}

// Whether the closed segments ab and cd meet.
bool segments_meet(const glm::dvec2 &a, const glm::dvec2 &b, const glm::dvec2 &c,
                   const glm::dvec2 &d) {
    const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
                 o4 = orient(c, d, b);
    if (((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) &&
        ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0)))
        return true;
    const auto on = [](const glm::dvec2 &p, const glm::dvec2 &r, const glm::dvec2 &x, double o) {
        return o == 0.0 && std::min(p.x, r.x) <= x.x && x.x <= std::max(p.x, r.x) &&
               std::min(p.y, r.y) <= x.y && x.y <= std::max(p.y, r.y);
    };
    return on(a, b, c, o1) || on(a, b, d, o2) || on(c, d, a, o3) || on(c, d, b, o4);
}

// Whether the chord from node i towards q[j] leaves i into the polygon (strictly inside the angle
// of its two sides at i).
bool in_cone(const glm::dvec2 *q, int n, int i, int j) {
    const glm::dvec2 &a = q[i], &prev = q[(i + n - 1) % n], &next = q[(i + 1) % n];
    if (orient(a, next, prev) >= 0.0) // convex at i
        return orient(a, q[j], prev) > 0.0 && orient(q[j], a, next) > 0.0;
    return !(orient(a, q[j], next) >= 0.0 && orient(q[j], a, prev) >= 0.0);
}

} // namespace

bool is_ring_chord(const glm::dvec2 *q, int n, int i, int j) {
    if ((i + 1) % n == j || (j + 1) % n == i)
        return true;
    if (!in_cone(q, n, i, j) || !in_cone(q, n, j, i))
        return false;
    for (int a = 0; a < n; ++a) {
        const int b = (a + 1) % n;
        if (a != i && a != j && b != i && b != j && segments_meet(q[i], q[j], q[a], q[b]))
            return false;
    }
    return true;
}

int clip_ears(const glm::dvec2 *q, int n, RingTriangle *out) {
    if (n < 3 || n > k_max_ring)
        return -1;
    std::array<std::uint8_t, k_max_ring> prev, next;
    std::array<double, k_max_ring> quality;
    std::array<bool, k_max_ring> delaunay; // known to be a Delaunay ear
    for (int i = 0; i < n; ++i) {
        prev[i] = std::uint8_t((i + n - 1) % n);
        next[i] = std::uint8_t((i + 1) % n);
        delaunay[i] = false;
    }
    for (int i = 0; i < n; ++i)
        quality[i] = ear_quality(q, next.data(), prev[i], i, next[i]);
    int first = 0, count = 0;
    std::array<std::uint8_t, k_max_ring> order;
    for (int remaining = n; remaining > 3; --remaining) {
        int valid = 0;
        int i = first;
        do {
            if (quality[i] >= 0.0)
                order[valid++] = std::uint8_t(i);
            i = next[i];
        } while (i != first);
        if (valid == 0)
            return -1; // no erasable ear: the ring is not a simple ccw polygon in this plane
        for (int k = 1; k < valid; ++k) // insertion sort by quality, best first: a handful of ears
            for (int j = k; j > 0 && quality[order[j]] > quality[order[j - 1]]; --j)
                std::swap(order[j], order[j - 1]);
        int best = order[0];
        for (int k = 0; k < valid; ++k) {
            const int e = order[k];
            if (delaunay[e] || is_delaunay_ear(q, next.data(), prev[e], e, next[e])) {
                delaunay[e] = true;
                best = e;
                break;
            }
        }
        const int a = prev[best], c = next[best];
        out[count++] = {std::uint8_t(a), std::uint8_t(best), std::uint8_t(c)};
        next[a] = std::uint8_t(c);
        prev[c] = std::uint8_t(a);
        if (first == best)
            first = c;
        quality[a] = ear_quality(q, next.data(), prev[a], a, c);
        quality[c] = ear_quality(q, next.data(), a, c, next[c]);
        delaunay[a] = delaunay[c] = false;
    }
    const int a = first, b = next[a], c = next[b];
    if (orient(q[a], q[b], q[c]) <= 0.0)
        return -1;
    out[count++] = {std::uint8_t(a), std::uint8_t(b), std::uint8_t(c)};
    return count;
}

RingOrientation ring_orientation(std::span<const glm::dvec2> ring) {
    double area2 = 0.0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const glm::dvec2 &a = ring[i];
        const glm::dvec2 &b = ring[(i + 1) % ring.size()];
        area2 += a.x * b.y - b.x * a.y;
    }
    return area2 > 0.0   ? RingOrientation::ccw
           : area2 < 0.0 ? RingOrientation::cw
                         : RingOrientation::degenerate;
}

bool is_erasable_ear(std::span<const glm::dvec2> ring, int i) {
    const int n = int(ring.size());
    if (n < 3 || n > k_max_ring)
        return false;
    std::array<std::uint8_t, k_max_ring> next;
    for (int j = 0; j < n; ++j)
        next[j] = std::uint8_t((j + 1) % n);
    return ear_quality(ring.data(), next.data(), (i + n - 1) % n, i, (i + 1) % n) >= 0.0;
}

std::vector<RingTriangle> triangulate_ring(std::span<const glm::dvec2> ring) {
    std::array<RingTriangle, k_max_ring> out;
    const int count = clip_ears(ring.data(), int(ring.size()), out.data());
    if (count < 0)
        return {};
    return {out.begin(), out.begin() + count};
}

} // namespace tinlod::erase
