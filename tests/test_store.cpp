// The quad-tree store on disk: round trip against the in-memory tree, partial reads, the cache cap,
// and rejection of corrupt, truncated and foreign files; the `build` and `retrieve` commands on it.
#include "assets.hpp"

#include "tinlod/error.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/store.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

using namespace tinlod;
using namespace tinlod::test;

namespace {

View make_view(glm::dvec3 eye, glm::dvec3 at) {
    View v;
    v.eye = eye;
    v.at = at;
    return v;
}

std::string read_all(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void write_all(const std::string &path, const std::string &bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

// A near view over the south-west corner of N42E001 (about 82 x 111 km), looking north-east.
View near_view(const Heightfield &hf) {
    return make_view({6000, 8000, hf.at(70, 90) + 300.0}, {20000, 25000, 600});
}

std::string error_of(const std::function<void()> &f) {
    try {
        f();
    } catch (const Error &e) {
        return e.what();
    }
    return "";
}

struct StoreFixture : public ::testing::Test {
    static void SetUpTestSuite() {
        hf = new Heightfield(load_heightfield(asset("N42E001.hgt")));
        tree = new QuadTree(*hf);
        dir = new std::string(temp_dir());
        path = new std::string(*dir + "/n42.tlq");
        write_store(*tree, *path);
    }
    static void TearDownTestSuite() {
        delete hf;
        delete tree;
        delete dir;
        delete path;
    }
    static Heightfield *hf;
    static QuadTree *tree;
    static std::string *dir;
    static std::string *path;
};
Heightfield *StoreFixture::hf = nullptr;
QuadTree *StoreFixture::tree = nullptr;
std::string *StoreFixture::dir = nullptr;
std::string *StoreFixture::path = nullptr;

} // namespace

TEST_F(StoreFixture, RetrievalFromTheStoreEqualsRetrievalFromMemory) {
    EXPECT_TRUE(is_store_file(*path));
    EXPECT_FALSE(is_store_file(asset("N42E001.hgt")));
    auto owned = std::make_unique<TileStore>(*path);
    TileStore *store = owned.get();
    EXPECT_EQ(store->frame().width, hf->width);
    EXPECT_EQ(store->frame().dx, hf->dx);
    EXPECT_EQ(store->frame().crs, hf->crs);
    QuadTreeLod from_disk(std::move(owned));
    QuadTreeLod in_memory(*tree);
    const double span = (hf->width - 1) * hf->dx;
    for (const View &view :
         {near_view(*hf), make_view({0.5 * span, 0.5 * span, 8000}, {0.5 * span, 0.5 * span, 0}),
          make_view({-0.5 * span, -0.5 * span, 4000}, {0.5 * span, 0.5 * span, 500})})
        for (double tol : {0.5, 2.0}) {
            const Retrieval &a = from_disk.retrieve(view, {tol, false});
            const Retrieval &b = in_memory.retrieve(view, {tol, false});
            EXPECT_EQ(a.triangles, b.triangles);
            EXPECT_EQ(a.nodes, b.nodes);
            EXPECT_EQ(a.z, b.z);
            for (std::size_t n = 0; n < a.nodes.size(); ++n)
                ASSERT_EQ(a.z[n], hf->z[a.nodes[n]]);
        }
    const Heightfield back = store->heightfield();
    EXPECT_EQ(back.z, hf->z);
}

TEST_F(StoreFixture, NearViewReadsOnlyPartOfTheTilesAndCacheHolds) {
    StoreOptions so;
    so.cache_mb = 1.0;
    auto owned = std::make_unique<TileStore>(*path, so);
    TileStore *store = owned.get();
    QuadTreeLod lod(std::move(owned));
    const View view = near_view(*hf);
    const Retrieval &r = lod.retrieve(view, {1.0, true});
    const StoreStats first = store->last_stats();
    EXPECT_GT(first.tiles_read, 0);
    EXPECT_LT(first.tiles_read, store->tile_count());
    EXPECT_LT(first.bytes_read, store->file_bytes());
    // The cap holds once the view is done.
    EXPECT_LE(store->resident_bytes(), 1024 * 1024);
    EXPECT_GT(first.tiles_evicted, 0);
    ErrorOptions eo;
    eo.model = Significance::screen(view);
    EXPECT_LE(measure_error(*hf, r.triangles, eo).max_screen_px, 1.0 + 1e-9);
    // The same view again reads only what was evicted; a cache large enough reads nothing.
    lod.retrieve(view, {1.0, true});
    EXPECT_LE(store->last_stats().tiles_read, first.tiles_read);
    StoreOptions big;
    big.cache_mb = 1024;
    auto owned2 = std::make_unique<TileStore>(*path, big);
    TileStore *store2 = owned2.get();
    QuadTreeLod lod2(std::move(owned2));
    lod2.retrieve(view, {1.0, true});
    EXPECT_EQ(store2->last_stats().tiles_read, first.tiles_read);
    lod2.retrieve(view, {1.0, true});
    EXPECT_EQ(store2->last_stats().tiles_read, 0);
}

TEST_F(StoreFixture, FlippedByteInATileIsDetected) {
    const std::string bytes = read_all(*path);
    const std::string bad = *dir + "/flipped.tlq";
    // The last byte of the file lies in the last tile (tiles are written last, page aligned).
    std::string flipped = bytes;
    flipped[flipped.size() - 5] ^= 0x10;
    write_all(bad, flipped);
    TileStore *store = nullptr;
    auto owned = std::make_unique<TileStore>(bad);
    store = owned.get();
    const std::string whole = error_of([&] { store->heightfield(); });
    EXPECT_NE(whole.find("checksum"), std::string::npos) << whole;
    EXPECT_NE(whole.find(bad), std::string::npos) << whole;
    // A retrieval that reaches the tile (full resolution) fails with a clear error.
    QuadTreeLod lod(std::move(owned));
    const std::string msg = error_of([&] { lod.retrieve(near_view(*hf), {0.0, false}); });
    EXPECT_NE(msg.find("corrupt tile"), std::string::npos) << msg;
    // A flip in the header or directory is caught on opening.
    for (std::size_t at : {std::size_t(20), std::size_t(300)}) {
        std::string head = bytes;
        head[at] ^= 0x01;
        write_all(bad, head);
        const std::string e = error_of([&] { TileStore s(bad); });
        EXPECT_NE(e.find("corrupt"), std::string::npos) << at << ": " << e;
    }
}

TEST_F(StoreFixture, TruncatedAndForeignFilesAreRejected) {
    const std::string bytes = read_all(*path);
    const std::string bad = *dir + "/bad.tlq";
    for (std::size_t keep : {std::size_t(0), std::size_t(7), std::size_t(100), std::size_t(5000),
                             bytes.size() / 2, bytes.size() - 1}) {
        write_all(bad, bytes.substr(0, keep));
        const std::string e = error_of([&] { TileStore s(bad); });
        EXPECT_FALSE(e.empty()) << "kept " << keep;
        EXPECT_TRUE(e.find("truncated") != std::string::npos ||
                    e.find("too short") != std::string::npos)
            << "kept " << keep << ": " << e;
    }
    const std::string foreign = error_of([&] { TileStore s(asset("N42E001.hgt")); });
    EXPECT_NE(foreign.find("not a tinlod quad-tree store"), std::string::npos) << foreign;
    std::string version = bytes;
    version[8] = 9;
    write_all(bad, version);
    const std::string v = error_of([&] { TileStore s(bad); });
    EXPECT_NE(v.find("version 9"), std::string::npos) << v;
    EXPECT_NE(error_of([&] { TileStore s(*dir + "/missing.tlq"); }).find("cannot open"),
              std::string::npos);
}

TEST(StoreCli, BuildThenRetrieveFromTheStore) {
    const std::string dir = temp_dir();
    const std::string store = dir + "/n42.tlq";
    const RunResult b = run_cli("build '" + asset("N42E001.hgt") + "' -o '" + store + "'");
    ASSERT_EQ(b.status, 0) << b.err;
    const RunResult r = run_cli("retrieve '" + store +
                                "' --eye 6000,8000,1400 --at 20000,25000,600 --tol 1 --cull "
                                "--check -o '" +
                                dir + "/near.ply' --stats '" + dir + "/s.json'");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto stats = nlohmann::json::parse(read_all(dir + "/s.json"));
    EXPECT_GT(stats["store"]["tiles_read"].get<std::int64_t>(), 0);
    EXPECT_LT(stats["store"]["tiles_read"].get<std::int64_t>(),
              stats["store"]["tiles_total"].get<std::int64_t>());
    EXPECT_GT(stats["store"]["bytes_read"].get<std::int64_t>(), 0);
    EXPECT_LE(stats["error"]["max_screen_px"].get<double>(), 1.0 + 1e-9);
    EXPECT_EQ(stats["error"]["uncovered_samples"].get<std::int64_t>(), 0);
    EXPECT_LT(stats["output"]["nodes"].get<std::int64_t>(),
              stats["input"]["nodes"].get<std::int64_t>());
    EXPECT_TRUE(std::filesystem::exists(dir + "/near.ply"));
    // The same view from the DEM gives the same TIN.
    const RunResult m = run_cli("retrieve '" + asset("N42E001.hgt") +
                                "' --eye 6000,8000,1400 --at 20000,25000,600 --tol 1 --cull -o '" +
                                dir + "/mem.ply' --stats '" + dir + "/m.json'");
    ASSERT_EQ(m.status, 0) << m.err;
    const auto ms = nlohmann::json::parse(read_all(dir + "/m.json"));
    EXPECT_EQ(ms["output"], nlohmann::json({{"file", dir + "/mem.ply"},
                                            {"nodes", stats["output"]["nodes"]},
                                            {"triangles", stats["output"]["triangles"]}}));
    // A corrupt store: one error line, non-zero exit, no output file.
    std::string bytes = read_all(store);
    bytes[bytes.size() - 5] ^= 0x40;
    write_all(dir + "/bad.tlq", bytes);
    const RunResult bad = run_cli("retrieve '" + dir + "/bad.tlq' --eye 6000,8000,1400 --at " +
                                  "20000,25000,600 --tol 0 -o '" + dir + "/bad.ply'");
    EXPECT_NE(bad.status, 0);
    EXPECT_NE(bad.err.find("corrupt tile"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/bad.ply"));
    // --full from a store gives the whole grid.
    const std::string small = dir + "/squared.tlq";
    ASSERT_EQ(run_cli("build '" + asset("dem_squared.tif") + "' -o '" + small + "'").status, 0);
    const RunResult full = run_cli("retrieve '" + small + "' --full -o '" + dir +
                                   "/full.ply' --stats '" + dir + "/f.json'");
    ASSERT_EQ(full.status, 0) << full.err;
    const auto fs = nlohmann::json::parse(read_all(dir + "/f.json"));
    EXPECT_EQ(fs["output"]["nodes"].get<std::int64_t>(), 129 * 129);
    EXPECT_EQ(fs["output"]["triangles"].get<std::int64_t>(), 2 * 128 * 128);
    // An eye under the ground is refused.
    const RunResult under = run_cli("retrieve '" + store + "' --eye 40000,50000,10 --at " +
                                    "20000,25000,600 -o '" + dir + "/under.ply'");
    EXPECT_NE(under.status, 0);
    EXPECT_NE(under.err.find("below the terrain"), std::string::npos) << under.err;
}
