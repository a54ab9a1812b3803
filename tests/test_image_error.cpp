// The paper's claim made measurable: a TIN erased at tau = 1 px looks like the full grid from the
// same camera; at tau = 8 px the difference is visible, and the geometric screen error and the
// image error agree in direction.
#include "assets.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/image_metrics.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/render.hpp"

#include <gtest/gtest.h>

using namespace tinlod;

namespace {

struct Measured {
    ImageDifference image;
    double screen_px = 0.0;
    std::int64_t nodes = 0;
};

Measured erase_and_compare(Renderer &renderer, const Heightfield &hf, const View &view,
                           const Image &reference, double tau) {
    Mesh tin = grid_tin(hf);
    EraseOptions eo;
    eo.tolerance = tau;
    erase_nodes(tin, Significance::screen(view), eo);
    RenderOptions ro;
    ro.normal_source = &hf; // shaded as terrain engines do: by the DEM's normals
    ErrorOptions err;
    err.model = Significance::screen(view);
    return {compare_images(renderer.render(tin, view, ro), reference),
            measure_error(hf, tin, err).max_screen_px, std::int64_t(tin.n_vertices())};
}

} // namespace

TEST(ImageError, TauOneLooksLikeTheFullGridAndTauEightDoesNot) {
    std::string why;
    if (!render_available(&why))
        GTEST_SKIP() << "no OpenGL context: " << why;
    Renderer renderer;
    for (const char *file : {"dem_srtm30.tif", "crater_u16.png"}) {
        SCOPED_TRACE(file);
        const Heightfield hf = load_heightfield(tinlod::test::asset(file));
        const double w = (hf.width - 1) * hf.dx, h = (hf.height - 1) * hf.dy;
        View view; // low oblique from the south-west corner across the terrain
        view.eye = {-0.1 * w, -0.1 * h, hf.max_z() + 0.15 * std::max(w, h)};
        view.at = {0.6 * w, 0.7 * h, hf.min_z()};
        view.viewport_w = 960;
        view.viewport_h = 540;
        RenderOptions ro;
        ro.normal_source = &hf;
        const Image reference = renderer.render(grid_tin(hf), view, ro);
        const Measured fine = erase_and_compare(renderer, hf, view, reference, 1.0);
        const Measured coarse = erase_and_compare(renderer, hf, view, reference, 8.0);
        EXPECT_LT(fine.nodes, hf.size() / 2) << "tau = 1 must erase";
        EXPECT_LE(fine.screen_px, 1.0);
        EXPECT_GE(fine.image.psnr_db, 40.0);
        EXPECT_LE(fine.image.differing_share, 0.04); // measured 1.95 % and 2.76 %
        EXPECT_LT(coarse.nodes, fine.nodes);
        EXPECT_GT(coarse.screen_px, fine.screen_px);
        EXPECT_LT(coarse.image.psnr_db, fine.image.psnr_db - 3.0) << "visibly worse at tau = 8";
        EXPECT_GT(coarse.image.differing_share, fine.image.differing_share);
        std::printf("%s: tau 1: %lld nodes, %.3f px, %.1f dB, %.2f %% differ; tau 8: %lld nodes, "
                    "%.3f px, %.1f dB, %.2f %% differ\n",
                    file, (long long)fine.nodes, fine.screen_px, fine.image.psnr_db,
                    100 * fine.image.differing_share, (long long)coarse.nodes, coarse.screen_px,
                    coarse.image.psnr_db, 100 * coarse.image.differing_share);
    }
}
