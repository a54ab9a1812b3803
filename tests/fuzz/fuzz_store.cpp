// Fuzz target: the quad-tree store reader (.tlq): open, retrieve fixed views through the tile
// cache, read every sample back. Every section of a store carries a CRC-32, so byte mutations
// mostly meet the checksum checks; the first input byte picks whether the harness re-seals the
// checksums after mutation (to reach the parsing behind them) and the size of the cache (to reach
// eviction). The rest is the store.
#include "fuzz_input.hpp"

#include "tinlod/error.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/store.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

namespace {

void check(bool ok, const char *what) {
    if (!ok) {
        std::fprintf(stderr, "fuzz_store: invariant broken: %s\n", what);
        std::abort();
    }
}

std::uint32_t crc32(const std::uint8_t *p, std::size_t n) {
    static const auto table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k)
                c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < n; ++i)
        c = table[(c ^ p[i]) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

template <class T> T get(const std::vector<std::uint8_t> &b, std::size_t at) {
    T v;
    std::memcpy(&v, b.data() + at, sizeof(T));
    return v;
}

// Recomputes every checksum the layout of store.hpp names, wherever the (mutated) offsets leave
// the section inside the file: the tiles first, then the directory, top tree, corners, header.
void reseal(std::vector<std::uint8_t> &b) {
    if (b.size() < 132)
        return;
    auto inside = [&](std::uint64_t offset, std::uint64_t bytes) {
        return offset <= b.size() && bytes <= b.size() - offset;
    };
    auto seal = [&](std::uint64_t offset, std::uint64_t bytes, std::size_t crc_at) {
        if (inside(offset, bytes) && inside(crc_at, 4)) {
            const std::uint32_t c = crc32(b.data() + offset, bytes);
            std::memcpy(b.data() + crc_at, &c, 4);
        }
    };
    const auto tiles = get<std::uint32_t>(b, 68);
    const auto dir = get<std::uint64_t>(b, 72);
    for (std::uint64_t t = 0; t < tiles && inside(dir, (t + 1) * 24); ++t)
        seal(get<std::uint64_t>(b, dir + t * 24), get<std::uint64_t>(b, dir + t * 24 + 8),
             dir + t * 24 + 16);
    seal(dir, std::uint64_t{tiles} * 24, 120);
    seal(get<std::uint64_t>(b, 80), get<std::uint64_t>(b, 88), 112);
    seal(get<std::uint64_t>(b, 96), get<std::uint64_t>(b, 104), 116);
    const auto header = get<std::uint32_t>(b, 12);
    if (header >= 4)
        seal(0, header - 4, header - 4);
}

// Every triangle of a retrieval uses nodes of the retrieval and turns counter-clockwise on the
// grid.
void check_retrieval(const tinlod::Retrieval &r, const tinlod::GridFrame &frame) {
    check(r.nodes.size() == r.z.size(), "nodes and z differ in size");
    check(r.triangles.size() % 3 == 0 && !r.triangles.empty(), "no whole triangles");
    const std::uint64_t samples = std::uint64_t(frame.width) * std::uint64_t(frame.height);
    std::vector<bool> is_node(samples);
    for (std::uint32_t id : r.nodes) {
        check(id < samples, "a node outside the grid");
        check(!is_node[id], "a node is listed twice");
        is_node[id] = true;
    }
    for (std::size_t t = 0; t < r.triangles.size(); t += 3) {
        std::int64_t c[3], row[3];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t id = r.triangles[t + k];
            check(id < samples, "a triangle uses a sample outside the grid");
            check(is_node[id], "a triangle uses no node");
            c[k] = id % frame.width;
            row[k] = id / frame.width;
        }
        check((c[1] - c[0]) * (row[2] - row[0]) - (c[2] - c[0]) * (row[1] - row[0]) > 0,
              "a triangle is not counter-clockwise");
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    if (size < 1)
        return 0;
    std::vector<std::uint8_t> bytes(data + 1, data + size);
    if (data[0] & 1)
        reseal(bytes);
    static constexpr double k_cache_mb[] = {256, 0, 0.01, 0.1};
    tinlod::StoreOptions options;
    options.cache_mb = k_cache_mb[(data[0] >> 1) % 4];
    const std::string path = tinlod::fuzz::write_input(bytes.data(), bytes.size(), ".tlq");
    try {
        auto source = std::make_unique<tinlod::TileStore>(path, options);
        tinlod::TileStore &store = *source;
        tinlod::QuadTreeLod lod(std::move(source));
        const tinlod::GridFrame &frame = lod.frame();
        const double w = (frame.width - 1) * frame.dx, h = (frame.height - 1) * frame.dy;
        // The root's box, when the root has one (a one-cell grid is a single leaf).
        const float zmax = lod.layout().levels() > 1 ? store.bound(0, 0, 0).zmax : 0.0f;
        const double top = std::isfinite(zmax) ? zmax : 0.0;
        tinlod::View near, above;
        near.viewport_w = above.viewport_w = 640;
        near.viewport_h = above.viewport_h = 360;
        near.eye = {0.1 * w, 0.1 * h, top + 0.02 * std::max(w, h)};
        near.at = {0.6 * w, 0.6 * h, top - 0.1 * std::max(w, h)};
        above.eye = {0.5 * w, 0.4 * h, top + 2 * std::max(w, h)};
        above.at = {0.5 * w, 0.5 * h, top};
        tinlod::validate(near);
        tinlod::validate(above);
        tinlod::RetrieveOptions ro;
        ro.cull = data[0] & 8;
        for (const tinlod::View *view : {&near, &above, &near}) {
            check_retrieval(lod.retrieve(*view, ro), frame);
            check(double(store.resident_bytes()) <= options.cache_mb * 1024 * 1024,
                  "the cache holds more than its cap after a retrieval");
        }
        // The full grid reads every tile; on small grids only, where it costs little.
        if (frame.width * frame.height <= 4096) {
            ro.tolerance = 0;
            check_retrieval(lod.retrieve(near, ro), frame);
        }
        const tinlod::Heightfield hf = store.heightfield();
        check(hf.z.size() == std::size_t(frame.width) * frame.height, "heightfield size");
    } catch (const tinlod::Error &) {
    }
    std::remove(path.c_str());
    return 0;
}
