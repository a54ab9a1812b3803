// Quad-tree retrieval speed (traversal + compact output per view), the OpenMesh conversion timed
// apart, and the build of the tree and its store, at tau = 1 px, 1920x1080, 60 degrees.
//
// Terrains: the real SRTM tile N42E001 (1201^2, meshes/), and a larger one made from it: bicubic
// (Catmull-Rom) enlargement to (1200*s+1)^2 samples over the same ground (cells s times smaller),
// plus fractal detail of the new scale: 4 octaves of value noise, the finest with amplitude
// 0.5 m at the new cell size, each coarser octave twice as wide and 1.6x as strong. The scale s is
// TINLOD_BENCH_SCALE (default 3.41, i.e. 4097^2; 13.65 gives 16385^2 and needs ~12 GB).
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/util.hpp"

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

float catmull_rom(float p0, float p1, float p2, float p3, float t) {
    return p1 + 0.5f * t * (p2 - p0 + t * (2 * p0 - 5 * p1 + 4 * p2 - p3 + t * (3 * (p1 - p2) + p3 - p0)));
}

float hash01(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
    std::uint32_t h = x * 374761393u + y * 668265263u + seed * 2246822519u;
    h = (h ^ (h >> 13)) * 1274126177u;
    return float((h ^ (h >> 16)) & 0xFFFFFF) / float(0xFFFFFF) - 0.5f;
}

float value_noise(double u, double v, std::uint32_t seed) {
    const auto x = std::uint32_t(u), y = std::uint32_t(v);
    const float fx = float(u - x), fy = float(v - y);
    const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
    const float a = hash01(x, y, seed), b = hash01(x + 1, y, seed), c = hash01(x, y + 1, seed),
                d = hash01(x + 1, y + 1, seed);
    return a + (b - a) * sx + (c - a) * sy + (a - b - c + d) * sx * sy;
}

Heightfield enlarge(const Heightfield& src, double scale) {
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

struct Terrain {
    Heightfield hf;
    std::unique_ptr<QuadTree> tree;
};

Terrain& terrain(const std::string& name) {
    static std::map<std::string, std::unique_ptr<Terrain>> cache;
    auto& slot = cache[name];
    if (!slot) {
        slot = std::make_unique<Terrain>();
        const auto meshes = std::filesystem::path(__FILE__).parent_path().parent_path() / "meshes";
        const Heightfield n42 = load_heightfield((meshes / "N42E001.hgt").string());
        const char* env = std::getenv("TINLOD_BENCH_SCALE");
        slot->hf = name == "n42" ? n42 : enlarge(n42, env ? std::atof(env) : 3.41);
        slot->tree = std::make_unique<QuadTree>(slot->hf);
    }
    return *slot;
}

// Low oblique view from the south-west quarter across the terrain, 300 m above the ground.
View bench_view(const Heightfield& hf) {
    const double ex = (hf.width - 1) * hf.dx, ey = (hf.height - 1) * hf.dy;
    View v;
    const int c = hf.width / 5, r = hf.height / 5;
    v.eye = {c * hf.dx, r * hf.dy, hf.at(c, r) + 300.0};
    v.at = {0.6 * ex, 0.7 * ey, hf.at(hf.width * 6 / 10, hf.height * 7 / 10)};
    return v;
}

void report(benchmark::State& state, const Terrain& t, const Retrieval& r) {
    state.counters["grid_samples"] = double(t.hf.size());
    state.counters["out_triangles"] = double(r.triangles.size() / 3);
    state.counters["node_ratio"] = double(r.nodes.size()) / double(t.hf.size());
    state.counters["tree_nodes"] = double(r.tree_nodes);
    state.counters["triangles_per_s"] = benchmark::Counter(
        double(r.triangles.size() / 3) * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["peak_rss_mb"] = peak_rss_mb();
}

void BM_Retrieve(benchmark::State& state, const std::string& name, bool cull) {
    Terrain& t = terrain(name);
    QuadTreeLod lod(*t.tree);
    const View view = bench_view(t.hf);
    const Retrieval* r = nullptr;
    for (auto _ : state) {
        r = &lod.retrieve(view, {1.0, cull});
        benchmark::DoNotOptimize(r->triangles.data());
    }
    report(state, t, *r);
}

void BM_RetrieveFromStore(benchmark::State& state, const std::string& name) {
    Terrain& t = terrain(name);
    const std::string path =
        (std::filesystem::temp_directory_path() / ("tinlod-bench-" + name + ".tlq")).string();
    write_store(*t.tree, path);
    {
        auto owned = std::make_unique<TileStore>(path);
        QuadTreeLod lod(std::move(owned));
        const View view = bench_view(t.hf);
        const Retrieval* r = nullptr;
        for (auto _ : state) {
            r = &lod.retrieve(view, {1.0, true});
            benchmark::DoNotOptimize(r->triangles.data());
        }
        report(state, t, *r);
    }
    std::filesystem::remove(path);
}

void BM_ToMesh(benchmark::State& state, const std::string& name) {
    Terrain& t = terrain(name);
    const Retrieval r = retrieve(*t.tree, bench_view(t.hf), {1.0, false});
    for (auto _ : state) {
        Mesh mesh = to_mesh(r, t.tree->frame());
        benchmark::DoNotOptimize(mesh.n_faces());
    }
    state.counters["out_triangles"] = double(r.triangles.size() / 3);
    state.counters["triangles_per_s"] = benchmark::Counter(
        double(r.triangles.size() / 3) * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Build(benchmark::State& state, const std::string& name) {
    Terrain& t = terrain(name);
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
BENCHMARK_CAPTURE(BM_Retrieve, n42_1201_cull, std::string("n42"), true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Retrieve, large, std::string("large"), false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Retrieve, large_cull, std::string("large"), true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RetrieveFromStore, n42_1201_cull, std::string("n42"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ToMesh, n42_1201, std::string("n42"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Build, n42_1201, std::string("n42"))->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Build, large, std::string("large"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

BENCHMARK_MAIN();
