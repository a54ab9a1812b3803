// `tinlod compare MESH REFERENCE --eye ... --at ... [--diff DIFF.png] [--json]`: how far a TIN or
// mesh is from its reference, geometrically (vertical and screen-space error against a DEM, or
// the symmetric Hausdorff distance against a mesh) and as seen (the two renders from one camera,
// compared by OpenImageIO).
#include "commands.hpp"
#include "outputs.hpp"

#include "tinlod/error.hpp"
#include "tinlod/hausdorff.hpp"
#include "tinlod/image_metrics.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/render.hpp"
#include "tinlod/util.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

namespace tinlod::cli {

static Register compare("compare", 70, [](CLI::App &cmd) {
    cmd.description("Compare a TIN or mesh with its reference DEM or mesh: vertical, screen-space "
                    "or Hausdorff error, and the image error of the two renders from one camera");
    struct Args {
        std::string input, reference, diff, color = "shade";
        bool json = false, dem_normals = false;
        double threshold = 2.0;
        std::int64_t samples = 200000;
        CameraOptions camera;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("MESH", args->input,
                   "the TIN or mesh to judge (a DEM or store is taken as its grid TIN)")
        ->required();
    cmd.add_option("REFERENCE", args->reference,
                   "the DEM or store (full grid TIN) or mesh it approximates")
        ->required();
    cmd.add_option("--diff", args->diff, "write |render - reference render| x8 as an image");
    declare_outputs(cmd, {{"--diff", &args->diff}});
    cmd.add_flag("--json", args->json, "print JSON instead of text");
    cmd.add_option("--threshold", args->threshold,
                   "grey levels (0..255) by which a pixel must differ to count as differing")
        ->check(real_in(0.0, 255.0))
        ->capture_default_str();
    cmd.add_option("--color", args->color, "colouring of both renders: shade | height")
        ->check(CLI::IsMember({"shade", "height"}))
        ->capture_default_str();
    cmd.add_flag("--dem-normals", args->dem_normals,
                 "shade both renders with the reference DEM's own normals, so the image error "
                 "shows only where the surface moves on screen");
    cmd.add_option("--samples", args->samples,
                   "Hausdorff sample points per mesh (mesh reference; 0: the vertices alone)")
        ->check(whole_in(0, 100000000))
        ->capture_default_str();
    args->camera.add(cmd, true);
    args->raster.add(cmd);
    // Peak memory per DEM sample of `tinlod compare (both rasters)`, measured
    // (docs/decisions/memory-per-sample.md).
    args->raster.bytes_per_sample = 570;
    return [args] {
        Stopwatch clock;
        const View view = args->camera.view();
        check_writable({args->diff});
        if (args->dem_normals && is_mesh_path(args->reference))
            throw UsageError("--dem-normals", "needs a DEM or store as REFERENCE");
        Renderer renderer; // before the long work, so a machine without OpenGL says so at once
        const Mesh mesh = is_mesh_path(args->input) ? read_mesh(args->input)
                                                    : grid_tin(args->raster.load(args->input));
        std::optional<Heightfield> dem;
        Mesh reference;
        if (is_mesh_path(args->reference)) {
            reference = read_mesh(args->reference);
        } else {
            dem = args->raster.load(args->reference);
            reference = grid_tin(*dem);
        }

        nlohmann::json out = {
            {"mesh",
             {{"file", args->input}, {"nodes", mesh.n_vertices()}, {"triangles", mesh.n_faces()}}},
            {"reference",
             {{"file", args->reference},
              {"nodes", reference.n_vertices()},
              {"triangles", reference.n_faces()}}}};
        if (dem) {
            ErrorOptions eo;
            eo.model = Significance::screen(view);
            const TinError e = measure_error(*dem, mesh, eo);
            out["geometry"] = {{"max_vertical", e.max_vertical},
                               {"rms_vertical", e.rms_vertical},
                               {"max_screen_px", e.max_screen_px},
                               {"samples", e.samples},
                               {"uncovered", e.uncovered}};
        } else {
            HausdorffOptions ho;
            ho.samples = args->samples;
            ho.model = Significance::screen(view);
            const HausdorffResult h = hausdorff(mesh, reference, ho);
            out["geometry"] = {{"hausdorff_max", h.max},
                               {"hausdorff_mean", h.mean},
                               {"hausdorff_rms", h.rms},
                               {"max_mesh_to_reference", h.max_a_to_b},
                               {"max_reference_to_mesh", h.max_b_to_a},
                               {"max_screen_px", h.max_screen_px},
                               {"max_screen_px_mesh_to_reference", h.max_screen_px_a_to_b},
                               {"max_screen_px_reference_to_mesh", h.max_screen_px_b_to_a},
                               {"samples", h.samples}};
        }

        RenderOptions ro;
        ro.color = args->color == "height" ? ColorMode::height : ColorMode::shade;
        Mesh::Point lo_p(1e30f), hi_p(-1e30f);
        for (auto v : reference.vertices()) {
            lo_p.minimize(reference.point(v));
            hi_p.maximize(reference.point(v));
        }
        // Both renders share the reference's height ramp and clipping planes, so only the
        // geometry differs between them.
        ro.z_min = lo_p[2];
        ro.z_max = hi_p[2];
        ro.clip = clip_range(reference, view);
        if (args->dem_normals)
            ro.normal_source = &*dem;
        const Image image = renderer.render(mesh, view, ro);
        const Image truth = renderer.render(reference, view, ro);
        ImageCompareOptions co;
        co.threshold = args->threshold;
        const ImageDifference d = compare_images(image, truth, co);
        if (!args->diff.empty())
            write_image(args->diff, difference_image(image, truth));
        out["image"] = {{"psnr_db", std::isfinite(d.psnr_db) ? nlohmann::json(d.psnr_db) : nullptr},
                        {"identical", d.max == 0.0},
                        {"differing_share", d.differing_share},
                        {"differing_pixels", d.differing_pixels},
                        {"threshold", args->threshold},
                        {"max", d.max},
                        {"mean", d.mean},
                        {"rms", d.rms},
                        {"dem_normals", args->dem_normals},
                        {"width", image.width},
                        {"height", image.height}};
        out["time_ms"] = clock.ms();

        if (args->json) {
            std::cout << out.dump(2) << '\n';
            return;
        }
        const auto &g = out["geometry"];
        std::printf("%s vs %s: %zu vs %zu triangles\n", args->input.c_str(),
                    args->reference.c_str(), mesh.n_faces(), reference.n_faces());
        if (dem)
            std::printf(
                "  vertical error: max %.4g, RMS %.4g; screen-space max %.3g px (%lld samples, "
                "%lld uncovered)\n",
                g["max_vertical"].get<double>(), g["rms_vertical"].get<double>(),
                g["max_screen_px"].get<double>(), g["samples"].get<long long>(),
                g["uncovered"].get<long long>());
        else
            std::printf(
                "  Hausdorff: max %.4g, mean %.4g, RMS %.4g (mesh->ref %.4g, ref->mesh %.4g; "
                "%lld samples); screen-space max %.3g px (mesh->ref %.3g, ref->mesh %.3g)\n",
                g["hausdorff_max"].get<double>(), g["hausdorff_mean"].get<double>(),
                g["hausdorff_rms"].get<double>(), g["max_mesh_to_reference"].get<double>(),
                g["max_reference_to_mesh"].get<double>(), g["samples"].get<long long>(),
                g["max_screen_px"].get<double>(),
                g["max_screen_px_mesh_to_reference"].get<double>(),
                g["max_screen_px_reference_to_mesh"].get<double>());
        std::printf("  image %dx%d: PSNR %s dB, %.4f%% of pixels differ by > %g grey levels, max "
                    "%g, mean %.4g\n",
                    image.width, image.height,
                    std::isfinite(d.psnr_db) ? std::to_string(d.psnr_db).c_str() : "inf",
                    100.0 * d.differing_share, args->threshold, d.max, d.mean);
    };
});

} // namespace tinlod::cli
