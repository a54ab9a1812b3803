// What decision 044's cuts in the erase's evaluations rely on
// (docs/decisions/044-erase-evaluations.md): on a grid TIN at a vertical bound, a hole that takes
// its min-max triangulation is measured from the programme's own scans of the new triangles, so
// each new triangle's largest deviation and worst sample must be what a scan of its samples gives,
// and an erasable hole's SP must hold them within the bound. Checked on every node of greedy TINs
// of real crops, against a scan of each triangle's box written here.
#include "assets.hpp"

#include "erase/erase_cost.hpp"
#include "erase/hole_geometry.hpp"
#include "erase/ring_triangulation.hpp"
#include "erase/state.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/greedy.hpp"
#include "tinlod/raster.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

using namespace tinlod;
using namespace tinlod::erase;
using tinlod::test::asset;

namespace {

// The largest deviation from `plane` (widened by `margin`) of the samples in the closed lattice
// triangle with corner nodes a, b, c but the corners, and the first sample in row order with it
// (-1 when none deviates): every sample of the corners' box, tested by the three edge functions.
std::pair<double, std::int32_t> worst_in_box(const EraserState &s, std::uint32_t a, std::uint32_t b,
                                             std::uint32_t c, const TrianglePlane &plane,
                                             double margin) {
    const std::int64_t w = s.input.grid_w;
    const std::int64_t x[3] = {a % w, b % w, c % w}, y[3] = {a / w, b / w, c / w};
    const std::int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    double most = 0.0;
    std::int32_t worst = -1;
    if (area == 0)
        return {most, worst};
    for (std::int64_t r = std::min({y[0], y[1], y[2]}); r <= std::max({y[0], y[1], y[2]}); ++r)
        for (std::int64_t col = std::min({x[0], x[1], x[2]}); col <= std::max({x[0], x[1], x[2]});
             ++col) {
            bool inside = true;
            for (int k = 0; k < 3; ++k) {
                const int l = (k + 1) % 3;
                const std::int64_t e = (x[l] - x[k]) * (r - y[k]) - (y[l] - y[k]) * (col - x[k]);
                inside = inside && (area > 0 ? e >= 0 : e <= 0);
            }
            const auto u = std::uint32_t(r * w + col);
            if (!inside || u == a || u == b || u == c)
                continue;
            // The sparse lattice's sample: its column's x and row's y as the mesh's floats.
            const double d = plane.deviation(double(s.input.lattice_x[std::size_t(col)]),
                                             double(s.input.lattice_y[std::size_t(r)]),
                                             double(s.input.lattice->z[std::size_t(u)]), margin);
            if (d > most) {
                most = d;
                worst = std::int32_t(u);
            }
        }
    return {most, worst};
}

struct Counts {
    int erasable = 0;  // holes within the bound
    int programme = 0; // of them, those whose triangulation is not the ears'
};

// Evaluates every erasable node of the greedy TIN of `hf` at `bound` and checks each hole within
// the bound against worst_in_box.
Counts check_holes(const Heightfield &hf, double bound) {
    GreedyOptions go;
    go.max_error = bound;
    go.seed_step = 16;
    Mesh mesh = to_sparse_lattice_mesh(greedy_tin(hf, go), hf);
    EraseOptions eo;
    eo.tolerance = bound;
    eo.lattice = &hf;
    NodeEraser eraser(mesh, Significance::vertical(), eo);
    EraserState &s = EraserAccess::state(eraser);
    EXPECT_GT(s.input.grid_w, 0u);
    EXPECT_NE(s.input.lattice, nullptr);
    Counts counts;
    for (auto v : mesh.vertices()) {
        const std::uint32_t x = node_of(s, v);
        if ((s.live.flags[x] & k_locked) || s.history.record_of[x] >= 0)
            continue;
        if (!evaluate(s, v, bound))
            continue;
        const Hole &h = s.scratch.hole;
        if (h.deferred || !(h.sp <= bound))
            continue;
        ++counts.erasable;
        double most = 0.0;
        for (int t = 0; t < h.ntri; ++t) {
            const RingTriangle &tri = h.tri[std::size_t(t)];
            const TrianglePlane &plane = h.frame[std::size_t(t)].plane;
            const auto [dev, worst] = worst_in_box(
                s, node_of(s, h.r[tri.a]), node_of(s, h.r[tri.b]), node_of(s, h.r[tri.c]), plane,
                plane.margin_over(h.p[tri.a], h.p[tri.b], h.p[tri.c]));
            EXPECT_EQ(h.tri_maxdev[std::size_t(t)], float_up(dev)) << "node " << x << " tri " << t;
            EXPECT_EQ(h.tri_worst[std::size_t(t)], worst) << "node " << x << " tri " << t;
            most = std::max(most, dev);
        }
        EXPECT_GE(h.sp, most) << "node " << x;
        std::array<RingTriangle, k_max_ring> ears;
        const int count = clip_ears(h.q.data(), h.n, ears.data());
        bool same = count == h.ntri;
        for (int t = 0; same && t < count; ++t)
            same = ears[std::size_t(t)].a == h.tri[std::size_t(t)].a &&
                   ears[std::size_t(t)].b == h.tri[std::size_t(t)].b &&
                   ears[std::size_t(t)].c == h.tri[std::size_t(t)].c;
        counts.programme += !same;
    }
    return counts;
}

} // namespace

// Crops of a real DEM and of a quantised 16-bit one, at a fine, a middle and a coarse bound: many
// holes take the min-max triangulation, and each is measured as a scan of its triangles would.
TEST(EraseEvaluations, MinMaxHolesMeasureAsTheirTrianglesSamples) {
    const Heightfield srtm =
        test::crop(load_heightfield(asset("dem_srtm30.tif")), 20, 30, 200, 160);
    const Heightfield crater =
        test::crop(load_heightfield(asset("crater_u16.png")), 40, 60, 180, 200);
    int programme = 0;
    for (const Heightfield *hf : {&srtm, &crater})
        for (const double bound : {1.0, 5.0, 20.0}) {
            const Counts counts = check_holes(*hf, bound);
            EXPECT_GT(counts.erasable, 50) << bound;
            programme += counts.programme;
        }
    EXPECT_GT(programme, 100);
}
