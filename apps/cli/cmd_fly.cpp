// `tinlod fly DEM|STORE|MESH --path PATH.csv [--tol 1] [--fps 4] [--check] [--frames DIR
// [--frames-eye X,Y,Z --frames-at X,Y,Z]] [--meshes DIR] [--stats FRAMES.csv]`: one TIN follows the
// observer along a camera path, frame after frame (lib/refine).
#include "commands.hpp"
#include "outputs.hpp"

#include "tinlod/camera_path.hpp"
#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/refine.hpp"
#include "tinlod/render.hpp"
#include "tinlod/store.hpp"
#include "tinlod/util.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

namespace tinlod::cli {

// tiles_read: a store's tiles, all on the first frame (fly reads a store whole), 0 for a DEM.
// entered: recovered samples there for the first time (the first frame's retrieval left them out).
// evaluations: erases tried by the update (each erased node's, and those that kept their node).
static const char *k_frame_header =
    "t,nodes,triangles,erased,recovered,tiles_read,ms_retrieve,"
    "ms_erase,ms_recover,ms_total,max_screen_px,entered,evaluations";

// A flight's frames are held as views (and a line of statistics each) before the first is flown.
constexpr double k_max_frames = 1e6;

static double percentile(std::vector<double> v, double q) {
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5))];
}

static Register fly("fly", 50, [](CLI::App &cmd) {
    cmd.description("Fly a camera path: one TIN follows the observer, erasing and recovering nodes "
                    "frame by frame");
    struct Args {
        std::string input, path, frames_dir, frames_eye, frames_at, meshes_dir, stats;
        std::string model = "screen";
        double tol = 1.0, fps = 4.0, hysteresis = 0.25, retrieve_share = 0.5;
        bool check = false;
        std::string viewport = "1920x1080";
        double fov = 60.0;
        RasterOptions raster;
    };
    auto args = std::make_shared<Args>();
    cmd.add_option("INPUT", args->input,
                   "DEM (GeoTIFF, PNG, EXR, .hgt, ...), quad-tree store (.tlq, read whole) or mesh")
        ->required();
    cmd.add_option("--path", args->path, "camera path CSV: t,eye_x,eye_y,eye_z,at_x,at_y,at_z")
        ->required();
    cmd.add_option("--tol", args->tol, "screen-space error bound tau, pixels")
        ->check(real_in(0.0, INFINITY, true))
        ->capture_default_str();
    cmd.add_option("--fps", args->fps, "frames per second of path time")
        ->check(real_in(0.0, 1000.0, true))
        ->capture_default_str();
    cmd.add_option("--hysteresis", args->hysteresis, "erase down to (1 - h) tau, recover above tau")
        ->check(real_in(0.0, 1.0, false, true))
        ->capture_default_str();
    cmd.add_option("--retrieve-share", args->retrieve_share,
                   "DEM, screen model: the first frame retrieves at this share of the erase's "
                   "bound; the samples it leaves out enter later where needed (0: full grid)")
        ->check(real_in(0.0, 1.0))
        ->capture_default_str();
    cmd.add_option("--model", args->model, "significance model: screen or paper")
        ->check(CLI::IsMember({"screen", "paper"}))
        ->capture_default_str();
    cmd.add_flag("--check", args->check,
                 "measure every frame's screen-space error exhaustively against every DEM sample");
    cmd.add_option("--frames", args->frames_dir,
                   "write one rendered PNG per frame into this folder (created when missing)");
    cmd.add_option("--frames-eye", args->frames_eye,
                   "draw the frames from this fixed camera X,Y,Z instead of the observer's, to see "
                   "the TIN follow the observer from outside")
        ->check(point_text());
    cmd.add_option("--frames-at", args->frames_at,
                   "the point the camera of --frames-eye looks toward X,Y,Z")
        ->check(point_text());
    cmd.add_option(
        "--meshes", args->meshes_dir,
        "write each frame's TIN into this folder (frame_NNNNN.ply; created when missing)");
    cmd.add_option("--stats", args->stats, "write one line of statistics per frame (CSV)");
    declare_outputs(cmd, {{"--stats", &args->stats}},
                    "The folders of --frames and --meshes are created when missing; their files "
                    "enter them together once the flight is through.");
    cmd.add_option("--fov", args->fov, "vertical field of view, degrees")
        ->check(real_in(0.0, 180.0, true, true))
        ->capture_default_str();
    cmd.add_option("--viewport", args->viewport, "viewport WxH, pixels (each side 1 to 65536)")
        ->check(viewport_text())
        ->capture_default_str();
    args->raster.add(cmd);
    // Peak memory per DEM sample of `tinlod fly --path`, measured
    // (docs/decisions/memory-per-sample.md).
    args->raster.bytes_per_sample = 180;
    return [args] {
        if (args->frames_eye.empty() != args->frames_at.empty())
            throw UsageError(args->frames_eye.empty() ? "--frames-at" : "--frames-eye",
                             "give both --frames-eye and --frames-at");
        if (!args->frames_eye.empty() && args->frames_dir.empty())
            throw UsageError("--frames-eye", "draws the frames of --frames: give --frames DIR");
        if (args->check && is_mesh_path(args->input))
            throw UsageError("--check", "measures against DEM samples: give a DEM, not a mesh");
        check_writable({args->stats});
        for (const std::string *folder : {&args->frames_dir, &args->meshes_dir})
            if (!folder->empty())
                check_writable_folder(*folder);
        const CameraPath path = read_camera_path(args->path);
        View base;
        base.fov_deg = args->fov;
        parse_viewport(args->viewport, base.viewport_w, base.viewport_h);
        // Counted in double: a path from t = 0 to 1e300 overflowed the int.
        const double frame_count = std::floor(path.duration() * args->fps + 1e-9) + 1.0;
        if (!(frame_count <= k_max_frames)) {
            char why[160];
            std::snprintf(why, sizeof why,
                          "the path lasts %g s: %g frames at --fps %g, more than %g",
                          path.duration(), frame_count, args->fps, k_max_frames);
            throw Error(args->path, why);
        }
        const int frames = std::max(1, int(frame_count));
        std::vector<View> views = path.sample(frames, base);
        for (const View &v : views)
            validate(v, args->path);
        std::optional<View> outside; // the fixed camera of --frames-eye
        if (!args->frames_eye.empty()) {
            outside = base;
            outside->eye = parse_vec3(args->frames_eye, "--frames-eye");
            outside->at = parse_vec3(args->frames_at, "--frames-at");
            try {
                validate(*outside, "--frames-eye/--frames-at");
            } catch (const Error &e) {
                throw UsageError(e.subject(), e.reason());
            }
        }

        StageTimes first_frame; // the run up to the first frame: load, retrieval and erase
        std::optional<Heightfield> hf;
        std::optional<Refiner> refiner;
        std::int64_t store_tiles = 0;
        RefineOptions options;
        options.tolerance = args->tol;
        options.hysteresis = args->hysteresis;
        options.retrieve_share = args->retrieve_share;
        options.significance.model = args->model == "paper" ? SpModel::paper : SpModel::screen;
        if (is_mesh_path(args->input)) {
            Mesh input = read_mesh(args->input);
            first_frame.lap("load");
            refiner.emplace(std::move(input), views.front(), options);
        } else {
            // A store's first retrieval reads the bounds it holds: no quad-tree is built.
            std::unique_ptr<TileStore> store;
            if (is_store_path(args->input)) {
                args->raster.check_store(args->input);
                store = std::make_unique<TileStore>(args->input);
                hf = store->heightfield();
                store_tiles = store->tile_count();
            } else {
                hf = load_heightfield(args->input, args->raster.load_options());
            }
            // Every keyframe, as well as every frame: a keyframe between two frames is flown
            // through all the same.
            for (const Keyframe &k : path.keys)
                check_eye_above(*hf, k.eye, args->path);
            for (const View &v : views)
                check_eye_above(*hf, v.eye, args->path);
            first_frame.lap("load");
            if (store)
                refiner.emplace(*hf, std::move(store), views.front(), options);
            else
                refiner.emplace(*hf, views.front(), options);
        }
        first_frame.lap("refine");

        std::unique_ptr<Renderer> renderer;
        RenderOptions ro;
        ro.wire = true;
        if (!args->frames_dir.empty())
            renderer = std::make_unique<Renderer>();
        if (outside) {
            // Coloured by height on one ramp for the whole flight (the DEM's, else the first
            // TIN's), so that a frame's colours do not shift as its nodes change.
            ro.color = ColorMode::height;
            if (hf) {
                ro.z_min = hf->min_z();
                ro.z_max = hf->max_z();
            } else {
                ro.z_min = INFINITY;
                ro.z_max = -INFINITY;
                for (auto v : refiner->mesh().vertices()) {
                    ro.z_min = std::min(ro.z_min, refiner->mesh().point(v)[2]);
                    ro.z_max = std::max(ro.z_max, refiner->mesh().point(v)[2]);
                }
            }
        }

        // The frames and TINs enter their folders together once the flight is through: a flight
        // that fails midway leaves none.
        std::optional<StagedFolder> frame_files, mesh_files;
        if (renderer)
            frame_files.emplace(args->frames_dir);
        if (!args->meshes_dir.empty())
            mesh_files.emplace(args->meshes_dir);
        std::ostringstream csv;
        csv << k_frame_header << '\n';
        std::vector<double> totals;
        double worst = 0.0;
        std::int64_t recovered_all = 0, erased_all = 0, reerased_all = 0, entered_all = 0;
        std::int64_t evaluations_all = 0, erased_after_first = 0;
        Progress progress("fly", frames);
        for (int i = 0; i < frames; ++i) {
            const FrameStats f = i == 0 ? refiner->first_frame() : refiner->update(views[i]);
            const UpdateStats &u = f.update;
            if (i > 0)
                totals.push_back(f.total_ms);
            recovered_all += u.recovered;
            erased_all += u.erased;
            reerased_all += u.reerased;
            entered_all += u.entered;
            if (i > 0) {
                evaluations_all += u.evaluations;
                erased_after_first += u.erased;
            }
            double max_px = -1.0; // not measured
            if (args->check) {
                ErrorOptions eo;
                eo.view = &views[i];
                const TinError e = measure_error(*hf, refiner->mesh(), eo);
                max_px = e.max_screen_px;
                worst = std::max(worst, max_px);
            }
            char name[32];
            if (renderer) {
                std::snprintf(name, sizeof name, "frame_%05d.png", i);
                const Image frame =
                    renderer->render(refiner->mesh(), outside ? *outside : views[i], ro);
                frame_files->write(name, [&](const std::string &to) { write_image(to, frame); });
            }
            if (mesh_files) {
                std::snprintf(name, sizeof name, "frame_%05d.ply", i);
                mesh_files->write(name,
                                  [&](const std::string &to) { write_mesh(refiner->mesh(), to); });
            }
            const double t =
                path.keys.front().t + (frames > 1 ? path.duration() * i / (frames - 1) : 0.0);
            char line[256];
            std::snprintf(line, sizeof line,
                          "%.3f,%lld,%lld,%lld,%lld,%lld,%.3f,%.3f,%.3f,%.3f,%s,%lld,%lld", t,
                          (long long)f.nodes, (long long)f.triangles, (long long)u.erased,
                          (long long)u.recovered, (long long)(i == 0 ? store_tiles : 0),
                          f.retrieve_ms, u.erase_ms + u.weights_ms, u.recover_ms, f.total_ms,
                          max_px < 0 ? "" : std::to_string(max_px).c_str(), (long long)u.entered,
                          (long long)(i == 0 ? 0 : u.evaluations));
            csv << line << '\n';
            progress.update(i + 1);
        }
        progress.finish();
        if (frame_files)
            frame_files->commit();
        if (mesh_files)
            mesh_files->commit();
        if (!args->stats.empty())
            write_atomically(args->stats, [&](const std::string &tmp) {
                std::ofstream out(tmp);
                out << csv.str();
                if (!out.flush())
                    throw Error(args->stats, "cannot write: " + std::string(std::strerror(errno)));
            });
        const auto &m = refiner->mesh();
        std::printf("%d frames, tau %.2f px: first frame %s, "
                    "then per frame p50 %.1f ms, p99 %.1f ms; %lld erased, %lld recovered in all "
                    "(%lld there for the first time, %lld erased again by the update that "
                    "recovered them); %.0f erases tried per frame, %.0f made; %.0f bytes per "
                    "node (TIN + history)%s\n",
                    frames, args->tol, first_frame.summary().c_str(), percentile(totals, 0.5),
                    percentile(totals, 0.99), (long long)erased_all, (long long)recovered_all,
                    (long long)entered_all, (long long)reerased_all,
                    double(evaluations_all) / std::max(frames - 1, 1),
                    double(erased_after_first) / std::max(frames - 1, 1),
                    double(refiner->bytes()) /
                        double(hf ? hf->size() : std::int64_t(m.n_vertices())),
                    args->check ? (", measured max " + std::to_string(worst) + " px").c_str() : "");
    };
});

} // namespace tinlod::cli
