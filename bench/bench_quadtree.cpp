// Quad-tree retrieval speed (traversal + compact output per view), the OpenMesh conversion timed
// apart, and the build of the tree and its store, at tau = 1 px, 1920x1080, 60 degrees.
//
// Terrains: the real SRTM tile N42E001 (1201^2, meshes/), and a larger one made from it by
// bench::enlarge (common.hpp) to (1200*s+1)^2 samples over the same ground. The scale s is
// TINLOD_BENCH_SCALE (default 3.41, i.e. 4097^2; 13.65 gives 16385^2 and needs ~12 GB).
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/util.hpp"

#include "common.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>

using namespace tinlod;

namespace {

struct Terrain {
    Heightfield hf;
    std::unique_ptr<QuadTree> tree;
};

Terrain &terrain(const std::string &name) {
    static std::map<std::string, std::unique_ptr<Terrain>> cache;
    auto &slot = cache[name];
    if (!slot) {
        slot = std::make_unique<Terrain>();
        const auto meshes = std::filesystem::path(__FILE__).parent_path().parent_path() / "meshes";
        const Heightfield n42 = load_heightfield((meshes / "N42E001.hgt").string());
        const char *env = std::getenv("TINLOD_BENCH_SCALE");
        slot->hf = name == "n42" ? n42 : bench::enlarge(n42, env ? std::atof(env) : 3.41);
        slot->tree = std::make_unique<QuadTree>(slot->hf);
    }
    return *slot;
}

// Low oblique view from the south-west quarter across the terrain, 300 m above the ground.
View bench_view(const Heightfield &hf) {
    const double ex = (hf.width - 1) * hf.dx, ey = (hf.height - 1) * hf.dy;
    View v;
    const int c = hf.width / 5, r = hf.height / 5;
    v.eye = {c * hf.dx, r * hf.dy, hf.at(c, r) + 300.0};
    v.at = {0.6 * ex, 0.7 * ey, hf.at(hf.width * 6 / 10, hf.height * 7 / 10)};
    return v;
}

void report(benchmark::State &state, const Terrain &t, const Retrieval &r) {
    state.counters["grid_samples"] = double(t.hf.size());
    state.counters["out_triangles"] = double(r.triangles.size() / 3);
    state.counters["node_ratio"] = double(r.nodes.size()) / double(t.hf.size());
    state.counters["tree_nodes"] = double(r.tree_nodes);
    state.counters["triangles_per_s"] = benchmark::Counter(
        double(r.triangles.size() / 3) * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["peak_rss_mb"] = peak_rss_mb();
}

void BM_Retrieve(benchmark::State &state, const std::string &name, bool cull) {
    Terrain &t = terrain(name);
    QuadTreeLod lod(*t.tree);
    const View view = bench_view(t.hf);
    const Retrieval *r = nullptr;
    for (auto _ : state) {
        r = &lod.retrieve(view, {1.0, cull});
        benchmark::DoNotOptimize(r->triangles.data());
    }
    report(state, t, *r);
}

void BM_RetrieveFromStore(benchmark::State &state, const std::string &name) {
    Terrain &t = terrain(name);
    const std::string path =
        (std::filesystem::temp_directory_path() / ("tinlod-bench-" + name + ".tlq")).string();
    write_store(*t.tree, path);
    {
        auto owned = std::make_unique<TileStore>(path);
        QuadTreeLod lod(std::move(owned));
        const View view = bench_view(t.hf);
        const Retrieval *r = nullptr;
        for (auto _ : state) {
            r = &lod.retrieve(view, {1.0, true});
            benchmark::DoNotOptimize(r->triangles.data());
        }
        report(state, t, *r);
    }
    std::filesystem::remove(path);
}

void BM_ToMesh(benchmark::State &state, const std::string &name) {
    Terrain &t = terrain(name);
    const Retrieval r = retrieve(*t.tree, bench_view(t.hf), {1.0, false});
    for (auto _ : state) {
        Mesh mesh = to_mesh(r, t.tree->frame());
        benchmark::DoNotOptimize(mesh.n_faces());
    }
    state.counters["out_triangles"] = double(r.triangles.size() / 3);
    state.counters["triangles_per_s"] = benchmark::Counter(
        double(r.triangles.size() / 3) * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Build(benchmark::State &state, const std::string &name) {
    Terrain &t = terrain(name);
    const std::string path =
        (std::filesystem::temp_directory_path() / ("tinlod-bench-build-" + name + ".tlq")).string();
    double tree_ms = 0, write_ms = 0;
    for (auto _ : state) {
        Stopwatch clock;
        const QuadTree tree(t.hf);
        tree_ms += clock.ms();
        clock.reset();
        write_store(tree, path);
        write_ms += clock.ms();
    }
    std::filesystem::remove(path);
    const double n = double(state.iterations());
    state.counters["samples_per_s"] =
        benchmark::Counter(double(t.hf.size()) * n, benchmark::Counter::kIsRate);
    state.counters["bounds_ms"] = tree_ms / n;
    state.counters["write_ms"] = write_ms / n;
}

} // namespace

BENCHMARK_CAPTURE(BM_Retrieve, n42_1201, std::string("n42"), false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Retrieve, n42_1201_cull, std::string("n42"), true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Retrieve, large, std::string("large"), false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Retrieve, large_cull, std::string("large"), true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RetrieveFromStore, n42_1201_cull, std::string("n42"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ToMesh, n42_1201, std::string("n42"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Build, n42_1201, std::string("n42"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Build, large, std::string("large"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

BENCHMARK_MAIN();
