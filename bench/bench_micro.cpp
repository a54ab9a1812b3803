// Google Benchmark micro-benchmarks of tinlod's hot paths: SP evaluation (significance.hpp), ring
// re-triangulation (triangulate_ring), quad-tree traversal (QuadTreeLod::retrieve), the grid TIN's
// mesh (grid_tin), node erase and recovery (NodeEraser), on the real SRTM tile N42E001 (meshes/)
// and its 513² crop.
#include "erase/ring_triangulation.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/screen_weight.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"

#include "common.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <random>
#include <vector>

using namespace tinlod;

namespace {

const Heightfield &n42() {
    static const Heightfield hf = load_heightfield(
        (std::filesystem::path(__FILE__).parent_path().parent_path() / "meshes/N42E001.hgt")
            .string());
    return hf;
}

const Heightfield &n42_513() {
    static const Heightfield hf = bench::crop(n42(), 513, 513);
    return hf;
}

// Low oblique view: 300 m above the ground a tenth into the terrain, looking at its centre.
View low_view(const Heightfield &hf) {
    const double w = (hf.width - 1) * hf.dx, h = (hf.height - 1) * hf.dy;
    View v;
    v.eye = {0.5 * w, 0.1 * h, hf.at(hf.width / 2, hf.height / 10) + 300.0};
    v.at = {0.5 * w, 0.5 * h, hf.at(hf.width / 2, hf.height / 2)};
    return v;
}

// SP of one node from its terms, for a million nodes spread over the terrain.
void BM_SpEvaluate(benchmark::State &state, SpModel model) {
    const Heightfield &hf = n42();
    const View view = low_view(hf);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<NodeTerms> terms(1 << 20);
    const double zmin = hf.min_z(), zmax = hf.max_z();
    for (NodeTerms &t : terms) {
        const glm::dvec3 p{u(rng) * (hf.width - 1) * hf.dx, u(rng) * (hf.height - 1) * hf.dy,
                           zmin + u(rng) * (zmax - zmin)};
        t.od = glm::length(p - view.eye);
        t.oa = observation_angle(view, p);
        t.delta = u(rng) * 10.0;
        t.ration = t.delta / 90.0;
        t.peripheral = peripheral_factor(view, p, {});
    }
    const Significance sp = Significance::of(model, view, {});
    for (auto _ : state)
        for (const NodeTerms &t : terms)
            benchmark::DoNotOptimize(significance(t, sp, 5000.0));
    state.SetItemsProcessed(state.iterations() * std::int64_t(terms.size()));
}

// The weight every node's deviation is measured with (k / OD * peripheral), over the grid TIN.
void BM_NodeWeights(benchmark::State &state) {
    const Mesh mesh = grid_tin(n42_513());
    const Weigher weigher(low_view(n42_513()), {});
    std::vector<float> weight(mesh.n_vertices());
    for (auto _ : state) {
        for (auto v : mesh.all_vertices()) {
            const auto &p = mesh.point(v);
            weight[std::size_t(v.idx())] = float(weigher({p[0], p[1], p[2]}));
        }
        benchmark::DoNotOptimize(weight.data());
    }
    state.SetItemsProcessed(state.iterations() * std::int64_t(mesh.n_vertices()));
}

// A star-shaped ring of n nodes (radius jittered by +-30 %), counter-clockwise.
void BM_TriangulateRing(benchmark::State &state) {
    const int n = int(state.range(0));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(0.7, 1.3);
    std::vector<std::vector<glm::dvec2>> rings(256);
    for (auto &ring : rings)
        for (int i = 0; i < n; ++i) {
            const double a = 2.0 * M_PI * i / n, r = jitter(rng);
            ring.push_back({r * std::cos(a), r * std::sin(a)});
        }
    for (auto _ : state)
        for (const auto &ring : rings)
            benchmark::DoNotOptimize(erase::triangulate_ring(ring).data());
    state.SetItemsProcessed(state.iterations() * std::int64_t(rings.size()));
}

// One view's traversal with the state of the previous view kept (the per-frame cost).
void BM_Traversal(benchmark::State &state, double tau) {
    static const QuadTree tree(n42());
    QuadTreeLod lod(tree);
    const View view = low_view(n42());
    const Retrieval *r = &lod.retrieve(view, {tau, false});
    for (auto _ : state) {
        r = &lod.retrieve(view, {tau, false});
        benchmark::DoNotOptimize(r->triangles.data());
    }
    state.counters["out_triangles"] = double(r->triangles.size() / 3);
    state.counters["tree_nodes"] = double(r->tree_nodes);
    state.SetItemsProcessed(state.iterations() * std::int64_t(r->triangles.size() / 3));
}

// The 1201² grid TIN's half-edge mesh (items: triangles): grid_tin (add_triangles, all sides
// paired at once) against OpenMesh's add_face per triangle, the way grid_tin built it before.
void BM_GridTin(benchmark::State &state, bool per_face) {
    const Heightfield &hf = n42();
    const std::uint32_t w = std::uint32_t(hf.width);
    for (auto _ : state) {
        if (!per_face) {
            benchmark::DoNotOptimize(grid_tin(hf).n_faces());
            continue;
        }
        Mesh mesh = grid_vertices(hf);
        for (std::uint32_t r = 0; r + 1 < std::uint32_t(hf.height); ++r)
            for (std::uint32_t c = 0; c + 1 < w; ++c) {
                const Mesh::VertexHandle a(int(r * w + c)), b(int(r * w + c + 1)),
                    d(int(r * w + w + c)), e(int(r * w + w + c + 1));
                if ((r + c) % 2 == 0) {
                    mesh.add_face(a, b, e);
                    mesh.add_face(a, e, d);
                } else {
                    mesh.add_face(a, b, d);
                    mesh.add_face(b, e, d);
                }
            }
        benchmark::DoNotOptimize(mesh.n_faces());
    }
    state.SetItemsProcessed(state.iterations() * 2 * std::int64_t(w - 1) * (hf.height - 1));
}

// Node erase at tau = 1 px of the 513² grid TIN (items: input triangles).
void BM_Erase(benchmark::State &state) {
    const Mesh grid = grid_tin(n42_513());
    const View view = low_view(n42_513());
    for (auto _ : state) {
        state.PauseTiming();
        Mesh mesh = grid;
        state.ResumeTiming();
        NodeEraser eraser(mesh, Significance::screen(view), EraseOptions{});
        benchmark::DoNotOptimize(eraser.erase().erased);
    }
    state.SetItemsProcessed(state.iterations() * std::int64_t(grid.n_faces()));
}

// Recovery of every node erased at tau = 1 px (items: nodes recovered).
void BM_Recover(benchmark::State &state) {
    Mesh mesh = grid_tin(n42_513());
    const View view = low_view(n42_513());
    NodeEraser eraser(mesh, Significance::screen(view), EraseOptions{});
    std::int64_t recovered = 0;
    for (auto _ : state) {
        state.PauseTiming();
        eraser.erase();
        state.ResumeTiming();
        recovered += eraser.recover_all();
    }
    state.SetItemsProcessed(recovered);
}

} // namespace

BENCHMARK_CAPTURE(BM_SpEvaluate, screen, SpModel::screen)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SpEvaluate, paper, SpModel::paper)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NodeWeights)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TriangulateRing)->Arg(4)->Arg(6)->Arg(8)->Arg(12)->Arg(24)->Arg(48);
BENCHMARK_CAPTURE(BM_Traversal, n42_tau1, 1.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Traversal, n42_tau4, 4.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GridTin, add_triangles, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GridTin, add_face, true)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Erase)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Recover)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
