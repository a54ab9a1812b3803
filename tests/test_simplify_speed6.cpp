// What the sixth round of `simplify --max-error` speed-ups relies on
// (docs/decisions/036-simplify-speed-6.md): the probe that stops once its answer is decided chooses
// the first stage the probe over all its windows chose; measure_error over a mesh (each vertex's
// corner once, in each face's corner order) gives what it gives over the same triangles by sample
// id; and the erase from the greedy start keeps every sample within the bound.
#include "assets.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/greedy.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

using namespace tinlod;
using tinlod::test::asset;

namespace {

// The erase's options of `simplify --max-error M` (vertical model).
EraseOptions bound(double m) {
    EraseOptions eo;
    eo.tolerance = m;
    return eo;
}

// The probe as it was before it could stop early (erase_dem.cpp's greedy_pays at main 149467a,
// with lib/src/erase/tuning.hpp's constants then: 3 x 3 windows, each 1/12 of the side and at least
// 16 samples, the insertion seeded every 16th sample, within 0.72 + 0.02 of their samples; its
// slope margin twice rounding_margin of the grid's extent at slope 1): the windows' share.
double full_probe_share(const Heightfield &hf, double m) {
    const int windows = 3, bw = std::max(16, hf.width / 12), bh = std::max(16, hf.height / 12);
    EXPECT_GE(hf.width, windows * bw);
    EXPECT_GE(hf.height, windows * bh);
    GreedyOptions go;
    go.max_error = m;
    go.slope_margin = 2.0 * 4.0 * 1.2e-7 *
                      std::max(1.0, std::max((hf.width - 1) * hf.dx, (hf.height - 1) * hf.dy));
    go.seed_step = 16;
    std::int64_t kept = 0, samples = 0;
    for (int i = 0; i < windows; ++i)
        for (int j = 0; j < windows; ++j) {
            const int x0 = (hf.width - bw) * (2 * i + 1) / (2 * windows),
                      y0 = (hf.height - bh) * (2 * j + 1) / (2 * windows);
            const Heightfield window = test::crop(hf, x0, y0, bw, bh);
            GreedyOptions wo = go;
            wo.max_nodes = window.size();
            kept += std::int64_t(greedy_tin(window, wo).tin.nodes.size());
            samples += window.size();
        }
    return double(kept) / double(samples);
}

// The mesh's faces as sample ids, in its face order and each face's corner order.
std::vector<std::uint32_t> face_samples(const Heightfield &hf, const Mesh &m) {
    std::vector<std::uint32_t> ids;
    for (auto f : m.faces())
        for (auto v : f.vertices()) {
            const auto &p = m.point(v);
            ids.push_back(std::uint32_t(std::lround(p[1] / hf.dy)) * std::uint32_t(hf.width) +
                          std::uint32_t(std::lround(p[0] / hf.dx)));
        }
    return ids;
}

// The measure's results, compared bit for bit.
auto results(const TinError &e) {
    return std::make_tuple(e.max_vertical, e.rms_vertical, e.samples, e.uncovered, e.worst_sample);
}

} // namespace

// On crops of two real DEMs, at bounds whose windows' share falls on both sides of the limit (some
// near it, where an early stop decides from part of the windows): the first stage is the greedy
// insertion exactly when the probe over all windows said it pays.
TEST(SimplifySpeed6, EarlyStoppingProbeChoosesAsTheFullProbe) {
    const Heightfield srtm =
        test::crop(load_heightfield(asset("dem_srtm30.tif")), 20, 30, 200, 200);
    const Heightfield n42 = test::crop(load_heightfield(asset("N42E001.hgt")), 300, 500, 200, 200);
    int pays = 0, not_pays = 0, near = 0;
    for (const Heightfield *hf : {&srtm, &n42})
        for (const double m : {1.0, 2.0, 5.0, 20.0}) {
            const double share = full_probe_share(*hf, m);
            const bool expected = share <= 0.72 + 0.02;
            (expected ? pays : not_pays) += 1;
            near += std::abs(share - 0.74) < 0.1;
            DemEraseStats stats;
            erase_dem(*hf, Significance::vertical(), bound(m), {}, &stats);
            EXPECT_EQ(stats.first_stage == FirstStage::greedy, expected)
                << (hf == &srtm ? "dem_srtm30" : "N42E001") << " at " << m << " m, share " << share;
        }
    EXPECT_GT(pays, 0);
    EXPECT_GT(not_pays, 0);
    EXPECT_GT(near, 0);
}

// A greedy TIN and the erase's output from it: measure_error over the mesh equals measure_error
// over its faces given as sample ids (corners by id, not by the mesh's points), bit for bit.
TEST(SimplifySpeed6, MeshMeasureIsTheMeasureOfItsFaces) {
    const Heightfield hf = test::crop(load_heightfield(asset("N42E001.hgt")), 300, 500, 160, 130);
    GreedyOptions go;
    go.max_error = 3.0;
    const Mesh greedy = to_sparse_lattice_mesh(greedy_tin(hf, go).tin, hf);
    // On its samples' heights, which the faces given as sample ids stand for.
    DemEraseOptions on_samples;
    on_samples.sample_heights = true;
    const Mesh erased = erase_dem(hf, Significance::vertical(), bound(3.0), on_samples);
    for (const Mesh *m : {&greedy, &erased}) {
        ASSERT_GT(m->n_faces(), 100u);
        const TinError by_mesh = measure_error(hf, *m);
        EXPECT_EQ(results(by_mesh), results(measure_error(hf, face_samples(hf, *m))));
        EXPECT_EQ(by_mesh.uncovered, 0);
        EXPECT_GT(by_mesh.max_vertical, 0.0);
    }
}

// The erase from the greedy start (which the probe chose) keeps every sample within the bound, by
// measure_error over all of them, at a coarse and a fine bound.
TEST(SimplifySpeed6, EraseFromTheGreedyStartStaysWithinTheBound) {
    const Heightfield hf = test::crop(load_heightfield(asset("crater_u16.png")), 40, 60, 200, 180);
    for (const double m : {1.0, 5.0}) {
        DemEraseStats stats;
        const Mesh tin = erase_dem(hf, Significance::vertical(), bound(m), {}, &stats);
        EXPECT_EQ(stats.first_stage, FirstStage::greedy) << m;
        const TinError e = measure_error(hf, tin);
        EXPECT_EQ(e.uncovered, 0);
        EXPECT_LE(e.max_vertical, m) << m;
        EXPECT_LT(std::int64_t(tin.n_faces()), 2 * hf.size() / 4) << m;
    }
}
