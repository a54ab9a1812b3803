// Fuzz target: greedy insertion (lib/greedy) on small grids. The input decodes into a grid of at
// most 40x40 heights, a cell size, a bound, a seed step and a node cap. The TIN must cover the
// rectangle without a fold-over (to_lattice_mesh builds it and refuses anything else), hold every
// sample within the bound (measured at every sample) unless the cap stopped it, stop at the cap
// when it did, and be Delaunay (no node strictly inside the circumcircle across an edge, exact on
// the integer lattice). A broken invariant aborts with a line naming it.
#include "tinlod/greedy.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/quadtree.hpp"

#include "fuzz_grid.hpp"

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <utility>

namespace {

using namespace tinlod;

void check(bool ok, const char *what) {
    if (!ok) {
        std::fprintf(stderr, "fuzz_greedy: invariant broken: %s\n", what);
        std::abort();
    }
}

// The xy area of the TIN, twice, and whether every face is counter-clockwise.
std::pair<double, bool> area2_and_ccw(const Mesh &mesh) {
    double total = 0.0;
    bool ccw = true;
    for (auto f : mesh.faces()) {
        auto v = f.vertices().begin();
        const auto a = mesh.point(*v++), b = mesh.point(*v++), c = mesh.point(*v);
        const double a2 = (double(b[0]) - a[0]) * (double(c[1]) - a[1]) -
                          (double(c[0]) - a[0]) * (double(b[1]) - a[1]);
        ccw = ccw && a2 > 0.0;
        total += a2;
    }
    return {total, ccw};
}

// Exact on lattice coordinates below 2^10: the determinant's terms stay under 2^53.
bool delaunay(const Retrieval &tin, std::int64_t width) {
    const auto &t = tin.triangles;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> apex;
    for (std::size_t i = 0; i < t.size(); i += 3)
        for (int k = 0; k < 3; ++k)
            apex[{t[i + k], t[i + (k + 1) % 3]}] = t[i + (k + 2) % 3];
    const auto x = [&](std::uint32_t n) { return std::int64_t(n) % width; };
    const auto y = [&](std::uint32_t n) { return std::int64_t(n) / width; };
    for (const auto &[edge, c] : apex) {
        const auto across = apex.find({edge.second, edge.first});
        if (across == apex.end())
            continue;
        const std::uint32_t a = edge.first, b = edge.second, d = across->second;
        const std::int64_t ax = x(a) - x(d), ay = y(a) - y(d), bx = x(b) - x(d), by = y(b) - y(d);
        const std::int64_t cx = x(c) - x(d), cy = y(c) - y(d);
        const std::int64_t det = (ax * ax + ay * ay) * (bx * cy - by * cx) -
                                 (bx * bx + by * by) * (ax * cy - ay * cx) +
                                 (cx * cx + cy * cy) * (ax * by - ay * bx);
        if (det > 0)
            return false;
    }
    return true;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    Heightfield hf;
    const double zscale = fuzz::take_grid(in, 40, hf);
    GreedyOptions options;
    static constexpr double k_bound[] = {1, 1e-6, 0.25, 4, 64, 1e9};
    options.max_error = in.PickValueInArray(k_bound) * zscale;
    static constexpr int k_seed[] = {0, 1, 2, 3, 16};
    options.seed_step = in.PickValueInArray(k_seed);
    options.max_nodes = in.ConsumeBool() ? in.ConsumeIntegralInRange(1, hf.width * hf.height) : 0;
    options.slope_margin = in.ConsumeBool() ? 1e-3 * zscale : 0.0;
    fuzz::take_heights(in, zscale, hf);

    const GreedyTin g = greedy_tin(hf, options);
    const std::size_t nodes = g.tin.nodes.size();
    check(nodes >= 4 && std::int64_t(nodes) <= hf.size(), "node count out of range");
    check(g.tin.triangles.size() % 3 == 0 && g.tin.z.size() == nodes, "malformed TIN arrays");
    if (g.stopped)
        check(options.max_nodes > 0 && std::int64_t(nodes) >= options.max_nodes,
              "stopped before the cap");
    const Mesh mesh = to_lattice_mesh(g.tin, hf);
    const auto [area2, ccw] = area2_and_ccw(mesh);
    const double area = (hf.width - 1) * hf.dx * (hf.height - 1) * hf.dy;
    check(ccw, "a face is not counter-clockwise in xy (fold-over)");
    check(std::abs(0.5 * area2 - area) <= 1e-9 * area, "the TIN does not cover the rectangle");
    const TinError measured = measure_error(hf, g.tin.triangles);
    check(measured.uncovered == 0, "a sample lies under no triangle");
    if (!g.stopped)
        check(measured.max_vertical <= options.max_error, "a sample is farther than the bound");
    check(delaunay(g.tin, hf.width), "an edge is not locally Delaunay");
    return 0;
}
