// The quantized-mesh-1.0 encoding of a tile and its gzip compression (tiles.hpp).
#include "geodesy.hpp"

#include "tinlod/error.hpp"
#include "tinlod/tiles.hpp"

#include <zlib.h>

#include <cstring>

namespace tinlod {

namespace {

using tiles::k_quantized_max;

struct Writer {
    std::vector<std::uint8_t> bytes;
    template <class T> void put(T x) {
        std::uint8_t b[sizeof(T)];
        std::memcpy(b, &x, sizeof(T)); // the format is little-endian, as this machine
        bytes.insert(bytes.end(), b, b + sizeof(T));
    }
    void align(std::size_t n) {
        while (bytes.size() % n != 0)
            bytes.push_back(0);
    }
};

std::uint16_t zig_zag(int delta) { return std::uint16_t((delta << 1) ^ (delta >> 31)); }

} // namespace

std::vector<std::uint8_t> encode_quantized_mesh(const TileMesh &tile) {
    const std::size_t n = tile.u.size();
    // Vertices renumbered in the order the triangles first use them, so the high-water-mark codes
    // stay small.
    std::vector<std::uint32_t> order, index(n, UINT32_MAX);
    for (const std::uint32_t v : tile.triangles)
        if (index[v] == UINT32_MAX) {
            index[v] = std::uint32_t(order.size());
            order.push_back(v);
        }
    for (std::uint32_t v = 0; v < n; ++v)
        if (index[v] == UINT32_MAX) {
            index[v] = std::uint32_t(order.size());
            order.push_back(v);
        }

    const GeoRect rect = tile_rect(tile.id);
    const auto lon = [&](std::uint16_t u) {
        return rect.west + double(u) / k_quantized_max * (rect.east - rect.west);
    };
    const auto lat = [&](std::uint16_t v) {
        return rect.south + double(v) / k_quantized_max * (rect.north - rect.south);
    };
    const double lo = tile.min_height, hi = tile.max_height;
    std::vector<glm::dvec3> points;
    double vmin = INFINITY, vmax = -INFINITY;
    for (const std::uint32_t v : order) {
        const double h = lo + double(tile.h[v]) / k_quantized_max * (hi - lo);
        vmin = std::min(vmin, h), vmax = std::max(vmax, h);
        points.push_back(tiles::ecef(lon(tile.u[v]), lat(tile.v[v]), h));
    }
    const tiles::Sphere sphere = tiles::bounding_sphere(points);
    const glm::dvec3 centre = tiles::ecef(0.5 * (rect.west + rect.east),
                                          0.5 * (rect.south + rect.north), 0.5 * (vmin + vmax));
    const glm::dvec3 occlusion = tiles::horizon_occlusion_point(points, sphere.centre, lo);

    Writer w;
    for (const double x : {centre.x, centre.y, centre.z})
        w.put(x);
    w.put(tile.min_height);
    w.put(tile.max_height);
    for (const double x : {sphere.centre.x, sphere.centre.y, sphere.centre.z, sphere.radius})
        w.put(x);
    for (const double x : {occlusion.x, occlusion.y, occlusion.z})
        w.put(x);

    w.put(std::uint32_t(n));
    for (const std::vector<std::uint16_t> *a : {&tile.u, &tile.v, &tile.h}) {
        int last = 0;
        for (const std::uint32_t v : order) {
            w.put(zig_zag(int((*a)[v]) - last));
            last = (*a)[v];
        }
    }

    // Indices of 32 bits past 65536 vertices (the specification; CesiumJS reads `> 64 * 1024`).
    const bool wide = n > 65536;
    const auto put_index = [&](std::uint32_t x) {
        if (wide)
            w.put(x);
        else
            w.put(std::uint16_t(x));
    };
    w.align(wide ? 4 : 2);
    w.put(std::uint32_t(tile.triangles.size() / 3));
    std::uint32_t highest = 0;
    for (const std::uint32_t v : tile.triangles) {
        const std::uint32_t k = index[v];
        put_index(highest - k);
        if (k == highest)
            ++highest;
    }
    for (const std::vector<std::uint32_t> *edge :
         {&tile.west, &tile.south, &tile.east, &tile.north}) {
        w.put(std::uint32_t(edge->size()));
        for (const std::uint32_t v : *edge)
            put_index(index[v]);
    }
    if (!tile.normals.empty()) {
        w.put(std::uint8_t(1)); // oct-encoded per-vertex normals
        w.put(std::uint32_t(2 * n));
        for (const std::uint32_t v : order) {
            w.put(tile.normals[2 * v]);
            w.put(tile.normals[2 * v + 1]);
        }
    }
    return w.bytes;
}

std::vector<std::uint8_t> gzip_bytes(const std::vector<std::uint8_t> &bytes) {
    z_stream s{};
    // 15 + 16: a gzip wrapper (no name, time 0: the same bytes give the same file).
    if (deflateInit2(&s, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY) != Z_OK)
        throw Error("gzip", "zlib cannot start a compression");
    std::vector<std::uint8_t> out(deflateBound(&s, uLong(bytes.size())) + 32);
    s.next_in = const_cast<Bytef *>(bytes.data());
    s.avail_in = uInt(bytes.size());
    s.next_out = out.data();
    s.avail_out = uInt(out.size());
    const int rc = deflate(&s, Z_FINISH);
    const std::size_t size = s.total_out;
    deflateEnd(&s);
    if (rc != Z_STREAM_END)
        throw Error("gzip", "zlib failed to compress a tile");
    out.resize(size);
    return out;
}

} // namespace tinlod
