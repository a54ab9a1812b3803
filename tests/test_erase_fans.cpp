// The node erase at a screen bound tries the fans of a hole whose Delaunay ears exceed the bound
// (docs/decisions/033-node-erase-vs-collapses.md): the bound still holds at every sample, measured
// by measure_error on the DEM, and the erase keeps no more nodes than the store's erase by
// half-edge collapses (lib/src/store_erase.cpp, another algorithm) at the same view and bound.
#include "assets.hpp"
#include "erase_fixtures.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/view.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace tinlod::test;

namespace {

// A near view down the tile and a low oblique one that retrieves across all of it.
struct Camera {
    std::string eye, at;
};
const Camera k_views[] = {{"8000,11000,1500", "50000,60000,800"},
                          {"60000,-3000,1600", "60000,40000,800"}};

tinlod::Mesh simplify(const std::string &input, const Camera &c, const std::string &name) {
    const std::string out = temp_dir() + "/" + name + ".ply";
    const RunResult r =
        run_cli("simplify '" + input + "' --eye " + c.eye + " --at " + c.at + " --tol 1 -o " + out);
    EXPECT_EQ(r.status, 0) << r.err;
    return tinlod::read_mesh(out);
}

} // namespace

TEST(EraseFans, ScreenBoundHoldsAtEverySample) {
    const tinlod::Heightfield hf = tinlod::load_heightfield(asset("N42E001.hgt"));
    for (const Camera &c : k_views) {
        const tinlod::Mesh tin = simplify(asset("N42E001.hgt"), c, "fans");
        tinlod::ErrorOptions eo;
        tinlod::View view; // the CLI's default fov and viewport
        view.eye = tinlod::parse_vec3(c.eye, "eye");
        view.at = tinlod::parse_vec3(c.at, "at");
        eo.model = tinlod::Significance::screen(view);
        const tinlod::TinError e = tinlod::measure_error(hf, tin, eo);
        EXPECT_LE(e.max_screen_px, 1.0 + 1e-9) << c.eye;
        EXPECT_GT(e.max_screen_px, 0.5) << c.eye << ": the erase did not use the bound";
        EXPECT_EQ(e.uncovered, 0) << c.eye;
        EXPECT_EQ(count_folded_faces(tin), 0) << c.eye;
    }
}

// Before the fans the node erase kept 1.40 times the collapses' nodes on the oblique view.
TEST(EraseFans, KeepsNoMoreNodesThanCollapses) {
    const std::string store = temp_dir() + "/fans.tlq";
    const RunResult built = run_cli("build '" + asset("N42E001.hgt") + "' -o '" + store + "'");
    ASSERT_EQ(built.status, 0) << built.err;
    const Camera &oblique = k_views[1];
    const tinlod::Mesh erased = simplify(asset("N42E001.hgt"), oblique, "erased");
    const tinlod::Mesh collapsed = simplify(store, oblique, "collapsed");
    EXPECT_LE(double(erased.n_vertices()), 1.02 * double(collapsed.n_vertices()));
}

// In the library, on the corners of every bundled DEM: the fans keep fewer nodes than the ears
// alone (EraseOptions::hole_fans false) at the same bound, measured at every sample.
TEST(EraseFans, FewerNodesThanTheEarsAloneWithinTheBound) {
    using tinlod::test::DemAsset;
    const DemAsset dems[] = {
        {"N42E001.hgt", false, 401}, {"dem_srtm30.tif", false, 0}, {"crater_u16.png", false, 401}};
    for (const DemAsset &a : dems) {
        const tinlod::Heightfield hf = tinlod::test::load_cropped(a);
        const tinlod::View view = tinlod::test::corner_view(hf);
        const tinlod::Significance screen = tinlod::Significance::screen(view);
        tinlod::EraseOptions ears, fans;
        ears.hole_fans = false;
        const tinlod::Mesh by_ears = tinlod::erase_dem(hf, screen, ears);
        const tinlod::Mesh by_fans = tinlod::erase_dem(hf, screen, fans);
        EXPECT_LT(by_fans.n_vertices(), by_ears.n_vertices()) << a.file;
        tinlod::ErrorOptions eo;
        eo.model = screen;
        const tinlod::TinError e = tinlod::measure_error(hf, by_fans, eo);
        EXPECT_LE(e.max_screen_px, 1.0 + 1e-9) << a.file;
        EXPECT_EQ(e.uncovered, 0) << a.file;
        EXPECT_EQ(count_folded_faces(by_fans), 0) << a.file;
    }
}
