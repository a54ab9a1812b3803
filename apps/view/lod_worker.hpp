// The viewer's live level of detail: a terrain or mesh opened from a file, the engine that turns a
// View into the TIN shown (behind a small interface, so the incremental refiner of lib/refine can
// replace it), and the worker thread that runs the engine off the render thread, latest request
// wins, publishing each result for the render thread to swap in.
#pragma once

#include "tinlod/focal.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <glm/glm.hpp>

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace tinlod::viewer {

enum class LodStages {
    retrieve,       // the quad-tree retrieval only (DEM, store); a mesh input is shown whole
    retrieve_erase, // then distance decay by node erase from the same view, bounded at every
                    // sample (as erase_dem; a store is read whole)
    refine,         // one TIN kept between views: erased and recovered incrementally (Refiner)
};

enum class ColorBy { shade, height, sp, level, error };

// What the engine computes for a view; a change of any field asks for a new TIN.
struct LodSettings {
    double tol_px = 1.0; // tau, pixels: retrieval and erase bound
    LodStages stages = LodStages::retrieve;
    SpModel model = SpModel::screen;  // SP model, screen or paper (erase ranking, SP colours)
    SignificanceOptions significance; // its parameters
    bool cull = true;                 // retrieval leaves the terrain outside the frustum coarse
    ColorBy color = ColorBy::height;  // which per-element scalars to compute
};

bool operator==(const LodSettings &a, const LodSettings &b);

// One TIN ready to draw, with what it took. Held by pointer: OpenMesh meshes copy when moved.
struct LodResult {
    std::uint64_t serial = 0; // of the request it answers
    View view;                // the view it was computed for
    LodSettings settings;
    Mesh mesh;                        // compact (no deleted elements)
    std::vector<float> vertex_scalar; // ColorBy::sp: one per vertex
    std::vector<float> face_scalar;   // ColorBy::level, error: one per face
    float scalar_min = 0.0f;          // value at the bottom of the colour map (subtracted from
                                      // the scalars above, which start at 0)
    float scalar_max = 0.0f;          // value at the top of the colour map, scalar_min subtracted
    std::unique_ptr<FocalIndex> surface; // for the focal point and terrain following
    FocalPoint focal;                    // of `view` on this TIN
    std::int64_t nodes = 0, triangles = 0;
    double retrieve_ms = 0.0, erase_ms = 0.0, color_ms = 0.0, total_ms = 0.0;
    double bound_px = 0.0;     // retrieval: the guaranteed screen error (0 for a mesh input)
    double erase_max_px = 0.0; // erase: the largest screen error it reached
};

// An input opened for viewing: its extent and the engine that makes its TINs.
struct SceneInfo {
    std::string path;
    std::string kind;            // "DEM", "store" or "mesh"
    glm::dvec3 lo{0.0}, hi{0.0}; // bounding box, world units
    std::int64_t input_nodes = 0, input_triangles = 0;
    bool error_colors = false; // ColorBy::error is available (a DEM: its samples are in memory)
    double load_ms = 0.0;
};

// Turns views into TINs. Called from one thread at a time (the worker's).
class LodEngine {
  public:
    virtual ~LodEngine() = default;
    // The TIN of `view`. Throws Error on failure (the worker reports it).
    virtual std::unique_ptr<LodResult> compute(const View &view, const LodSettings &settings) = 0;
};

// Height of the surface of `result` under the point (x, y) (the highest face there, if several), or
// nothing off the surface; `scene` bounds the search in z.
std::optional<double> ground_height(const LodResult &result, const SceneInfo &scene, double x,
                                    double y);

// Opens a DEM (read with `load`), a store (.tlq) or a mesh by its content / extension; throws Error
// naming the file.
std::unique_ptr<LodEngine> open_scene(const std::string &path, SceneInfo &info,
                                      const LoadOptions &load = {});

// Runs an engine on its own thread. request() never blocks on a computation; the render thread
// polls take() each frame.
class LodWorker {
  public:
    explicit LodWorker(std::unique_ptr<LodEngine> engine);
    ~LodWorker();
    LodWorker(const LodWorker &) = delete;
    LodWorker &operator=(const LodWorker &) = delete;

    // Asks for the TIN of `view`; replaces any request not started yet. Returns its serial.
    std::uint64_t request(const View &view, const LodSettings &settings);
    // The newest finished result not taken yet, or null.
    std::unique_ptr<LodResult> take();
    // Blocks until the request `serial` (or a later one) has finished; returns take().
    std::unique_ptr<LodResult> wait(std::uint64_t serial);
    bool busy() const;
    // The message of the last computation that threw (empty when none did).
    std::string error() const;

  private:
    void run();

    std::unique_ptr<LodEngine> engine_;
    mutable std::mutex mutex_;
    std::condition_variable wake_, done_;
    bool stop_ = false, pending_ = false, working_ = false;
    View view_;
    LodSettings settings_;
    std::uint64_t next_serial_ = 0, request_serial_ = 0, finished_serial_ = 0;
    std::unique_ptr<LodResult> result_;
    std::string error_;
    std::thread thread_;
};

} // namespace tinlod::viewer
