// Scenes, LOD engines and the worker thread of the viewer (lod_worker.hpp).
#include "lod_worker.hpp"

#include "tinlod/decimate.hpp"
#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/refine.hpp"
#include "tinlod/store.hpp"
#include "tinlod/util.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tinlod::viewer {

namespace {

glm::dvec3 to_glm(const Mesh::Point &p) { return {p[0], p[1], p[2]}; }

// Quad-tree level of each face: log2 of the extent over the side of a square of twice the face's
// area (xy area for TINs), so a face half of a leaf cell at level d gets d.
std::vector<float> face_levels(const Mesh &mesh, double extent, bool xy) {
    std::vector<float> level(mesh.n_faces(), 0.0f);
    for (auto f : mesh.faces()) {
        glm::dvec3 p[3];
        int i = 0;
        for (auto v : f.vertices())
            p[i++] = to_glm(mesh.point(v));
        glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double area2 = xy ? std::abs(n.z) : glm::length(n);
        level[f.idx()] =
            area2 > 0.0 ? float(std::max(0.0, std::log2(extent / std::sqrt(area2)))) : 0.0f;
    }
    return level;
}

// Screen error of each face of a TIN over the DEM samples it covers: the largest vertical
// deviation of a sample from the face times k / distance(eye, sample), pixels.
std::vector<float> face_errors(const Mesh &mesh, const QuadTree &tree, const View &view) {
    const GridFrame &g = tree.frame();
    const auto origin = find_origin_property(mesh);
    std::vector<float> error(mesh.n_faces(), 0.0f);
    if (!origin.is_valid())
        return error;
    const double k = view.k();
    const auto w = static_cast<std::int64_t>(g.width);
    for (auto f : mesh.faces()) {
        double c[3], r[3], z[3];
        int i = 0;
        for (auto v : f.vertices()) {
            const std::int64_t id = mesh.property(origin, v);
            c[i] = double(id % w);
            r[i] = double(id / w);
            z[i++] = mesh.point(v)[2];
        }
        const double area = (c[1] - c[0]) * (r[2] - r[0]) - (c[2] - c[0]) * (r[1] - r[0]);
        if (area == 0.0)
            continue;
        const auto c0 = std::uint32_t(std::min({c[0], c[1], c[2]}));
        const auto c1 = std::uint32_t(std::max({c[0], c[1], c[2]}));
        const auto r0 = std::uint32_t(std::min({r[0], r[1], r[2]}));
        const auto r1 = std::uint32_t(std::max({r[0], r[1], r[2]}));
        double worst = 0.0;
        for (std::uint32_t rr = r0; rr <= r1; ++rr)
            for (std::uint32_t cc = c0; cc <= c1; ++cc) {
                const double u = cc, v = rr;
                const double w0 = ((c[1] - u) * (r[2] - v) - (c[2] - u) * (r[1] - v)) / area;
                const double w1 = ((c[2] - u) * (r[0] - v) - (c[0] - u) * (r[2] - v)) / area;
                const double w2 = 1.0 - w0 - w1;
                if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9)
                    continue;
                const double zs = tree.elevation(cc, rr);
                const double dev = std::abs(zs - (w0 * z[0] + w1 * z[1] + w2 * z[2]));
                if (dev == 0.0)
                    continue;
                const double od = glm::length(glm::dvec3(u * g.dx, v * g.dy, zs) - view.eye);
                worst = std::max(worst, od > 0.0 ? dev * k / od : 0.0);
            }
        error[f.idx()] = float(worst);
    }
    return error;
}

// Value below which `share` of the finite values lie (0 when there are none).
float quantile(std::vector<float> values, double share) {
    std::erase_if(values, [](float v) { return !std::isfinite(v); });
    if (values.empty())
        return 0.0f;
    const auto n = std::size_t(share * double(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(n), values.end());
    return values[n];
}

// What every engine does after making its TIN: erase when asked, colours, the focal index.
class EngineBase : public LodEngine {
  protected:
    // `lattice`: the grid a sparse lattice TIN holds samples of (EraseOptions::lattice).
    void finish(LodResult &result, const View &view, const LodSettings &settings, double extent,
                bool tin, const Heightfield *lattice = nullptr) {
        Stopwatch clock;
        if (settings.stages == LodStages::retrieve_erase) {
            EraseOptions eo;
            eo.tolerance = settings.tol_px;
            eo.significance = settings.significance;
            eo.lattice = lattice;
            const EraseStats erased = erase_nodes(result.mesh, &view, eo);
            result.erase_ms = clock.ms();
            result.erase_max_px = erased.max_screen_px;
        }
        clock.reset();
        switch (settings.color) {
        case ColorBy::sp: {
            result.vertex_scalar = node_significance(result.mesh, &view, settings.significance);
            result.scalar_max = std::max(quantile(result.vertex_scalar, 0.95), 1e-6f);
            for (float &s : result.vertex_scalar)
                if (!std::isfinite(s))
                    s = result.scalar_max;
            break;
        }
        case ColorBy::level: {
            // The colour map spans the levels present.
            result.face_scalar = face_levels(result.mesh, extent, tin);
            const auto [lo, hi] =
                std::minmax_element(result.face_scalar.begin(), result.face_scalar.end());
            if (lo != result.face_scalar.end()) {
                result.scalar_min = std::floor(*lo);
                result.scalar_max = std::max(std::ceil(*hi) - result.scalar_min, 1.0f);
            }
            for (float &s : result.face_scalar)
                s -= result.scalar_min;
            break;
        }
        case ColorBy::error:
            result.face_scalar = errors(result.mesh, view);
            result.scalar_max = float(std::max(2.0 * settings.tol_px, 0.5));
            break;
        case ColorBy::shade:
        case ColorBy::height:
            break;
        }
        result.color_ms = clock.ms();
        result.surface = std::make_unique<FocalIndex>(result.mesh);
        result.focal = result.surface->cast(view);
        result.nodes = std::int64_t(result.mesh.n_vertices());
        result.triangles = std::int64_t(result.mesh.n_faces());
    }
    // Per-face screen errors against the input; zeros when the input is not in memory.
    virtual std::vector<float> errors(const Mesh &mesh, const View &) {
        return std::vector<float>(mesh.n_faces(), 0.0f);
    }
};

// DEM (in memory) or store (read partially): retrieval with a QuadTreeLod, or the refiner (its
// first frame a retrieval on the whole lattice, then the erase; a store is then read whole, once).
class GridEngine final : public EngineBase {
  public:
    explicit GridEngine(const Heightfield &hf) : hf_(hf), tree_(std::in_place, hf), lod_(*tree_) {}
    explicit GridEngine(std::unique_ptr<TileStore> store)
        : store_(store.get()), lod_(std::move(store)) {}

    std::unique_ptr<LodResult> compute(const View &view, const LodSettings &settings) override {
        if (settings.stages == LodStages::refine)
            return refine(view, settings);
        Stopwatch total;
        auto result = std::make_unique<LodResult>();
        // With the erase, both methods as `simplify` runs them (erase_dem): retrieval at half of
        // tau on the whole lattice, so the erase bounds every sample (a store is then read whole,
        // once, as for the refiner).
        const bool lattice = settings.stages == LodStages::retrieve_erase;
        if (lattice && !hf_)
            hf_ = store_->heightfield();
        RetrieveOptions ro;
        ro.tolerance =
            lattice ? DemEraseOptions{}.retrieve_share * settings.tol_px : settings.tol_px;
        ro.cull = settings.cull;
        if (lattice && settings.significance.model == SpModel::screen)
            ro.peripheral = &settings.significance; // the erase's weighted bound, as erase_dem
        const Retrieval &r = lod_.retrieve(view, ro);
        result->mesh = lattice ? to_sparse_lattice_mesh(r, *hf_) : to_mesh(r, lod_.frame());
        result->bound_px = r.bound_px;
        result->retrieve_ms = total.ms();
        const GridFrame &g = lod_.frame();
        finish(*result, view, settings, std::max((g.width - 1) * g.dx, (g.height - 1) * g.dy), true,
               lattice ? &*hf_ : nullptr);
        result->total_ms = total.ms();
        return result;
    }

  private:
    std::unique_ptr<LodResult> refine(const View &view, const LodSettings &settings) {
        Stopwatch total;
        auto result = std::make_unique<LodResult>();
        if (!refiner_ || refined_tol_ != settings.tol_px ||
            refined_model_ != settings.significance.model) {
            if (!hf_)
                hf_ = store_->heightfield();
            RefineOptions options;
            options.tolerance = settings.tol_px;
            options.significance = settings.significance;
            refiner_.reset();
            refiner_ = std::make_unique<Refiner>(*hf_, view, options);
            refined_tol_ = settings.tol_px;
            refined_model_ = settings.significance.model;
            result->erase_ms = refiner_->first_frame().total_ms;
        } else {
            const FrameStats f = refiner_->update(view);
            result->erase_ms = f.total_ms;
        }
        result->mesh = live_copy(refiner_->mesh());
        LodSettings shown = settings;
        shown.stages = LodStages::retrieve; // the erase is done: colour and index only
        const GridFrame &g = lod_.frame();
        finish(*result, view, shown, std::max((g.width - 1) * g.dx, (g.height - 1) * g.dy), true);
        result->total_ms = total.ms();
        return result;
    }

    std::vector<float> errors(const Mesh &mesh, const View &view) override {
        return tree_ ? face_errors(mesh, *tree_, view) : EngineBase::errors(mesh, view);
    }

    std::optional<Heightfield> hf_;
    TileStore *store_ = nullptr;
    std::optional<QuadTree> tree_;
    QuadTreeLod lod_;
    std::unique_ptr<Refiner> refiner_;
    double refined_tol_ = 0.0;
    SpModel refined_model_ = SpModel::screen;
};

// A mesh file: shown whole, or decimated by node erase from the view.
class MeshEngine final : public EngineBase {
  public:
    MeshEngine(Mesh mesh, double extent) : mesh_(std::move(mesh)), extent_(extent) {}

    std::unique_ptr<LodResult> compute(const View &view, const LodSettings &settings) override {
        Stopwatch total;
        auto result = std::make_unique<LodResult>();
        result->mesh = mesh_;
        finish(*result, view, settings, extent_, false);
        result->total_ms = total.ms();
        return result;
    }

  private:
    Mesh mesh_;
    double extent_;
};

} // namespace

bool operator==(const LodSettings &a, const LodSettings &b) {
    const SignificanceOptions &p = a.significance, &q = b.significance;
    return a.tol_px == b.tol_px && a.stages == b.stages && a.cull == b.cull && a.color == b.color &&
           p.model == q.model && p.cone_margin_px == q.cone_margin_px &&
           p.falloff_deg == q.falloff_deg && p.floor == q.floor && p.w_distance == q.w_distance &&
           p.w_angle == q.w_angle && p.w_ration == q.w_ration;
}

std::optional<double> ground_height(const LodResult &result, const SceneInfo &scene, double x,
                                    double y) {
    if (!result.surface)
        return std::nullopt;
    View down;
    down.eye = glm::dvec3(x, y, scene.hi.z + 1.0 + std::abs(scene.hi.z));
    down.at = glm::dvec3(x, y, scene.lo.z - 1.0);
    const FocalPoint hit = result.surface->cast(down);
    return hit.hit ? std::optional<double>(hit.point.z) : std::nullopt;
}

std::unique_ptr<LodEngine> open_scene(const std::string &path, SceneInfo &info,
                                      const LoadOptions &load) {
    Stopwatch clock;
    info = SceneInfo{};
    info.path = path;
    std::unique_ptr<LodEngine> engine;
    if (is_store_file(path)) {
        auto store = std::make_unique<TileStore>(path);
        const GridFrame &g = store->frame();
        info.kind = "store";
        const NodeBound root = store->layout().levels() > 1 ? store->bound(0, 0, 0) : NodeBound{};
        info.lo = {0.0, 0.0, root.zmin};
        info.hi = {(g.width - 1) * g.dx, (g.height - 1) * g.dy, root.zmax};
        info.input_nodes = std::int64_t(g.width) * g.height;
        info.input_triangles = 2 * std::int64_t(g.width - 1) * (g.height - 1);
        engine = std::make_unique<GridEngine>(std::move(store));
    } else if (is_mesh_path(path)) {
        Mesh mesh = read_mesh(path);
        info.kind = "mesh";
        info.lo = glm::dvec3(std::numeric_limits<double>::infinity());
        info.hi = -info.lo;
        for (auto v : mesh.vertices()) {
            info.lo = glm::min(info.lo, to_glm(mesh.point(v)));
            info.hi = glm::max(info.hi, to_glm(mesh.point(v)));
        }
        info.input_nodes = std::int64_t(mesh.n_vertices());
        info.input_triangles = std::int64_t(mesh.n_faces());
        const double extent = glm::length(info.hi - info.lo);
        engine = std::make_unique<MeshEngine>(std::move(mesh), extent);
    } else {
        const Heightfield hf = load_heightfield(path, load);
        info.kind = "DEM";
        info.lo = {0.0, 0.0, hf.min_z()};
        info.hi = {(hf.width - 1) * hf.dx, (hf.height - 1) * hf.dy, hf.max_z()};
        info.input_nodes = hf.size();
        info.input_triangles = 2 * std::int64_t(hf.width - 1) * (hf.height - 1);
        info.error_colors = true;
        engine = std::make_unique<GridEngine>(hf);
    }
    info.load_ms = clock.ms();
    return engine;
}

LodWorker::LodWorker(std::unique_ptr<LodEngine> engine)
    : engine_(std::move(engine)), thread_([this] { run(); }) {}

LodWorker::~LodWorker() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

std::uint64_t LodWorker::request(const View &view, const LodSettings &settings) {
    std::uint64_t serial;
    {
        std::lock_guard lock(mutex_);
        view_ = view;
        settings_ = settings;
        pending_ = true;
        serial = request_serial_ = ++next_serial_;
    }
    wake_.notify_one();
    return serial;
}

std::unique_ptr<LodResult> LodWorker::take() {
    std::lock_guard lock(mutex_);
    return std::move(result_);
}

std::unique_ptr<LodResult> LodWorker::wait(std::uint64_t serial) {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return finished_serial_ >= serial; });
    return std::move(result_);
}

bool LodWorker::busy() const {
    std::lock_guard lock(mutex_);
    return pending_ || working_;
}

std::string LodWorker::error() const {
    std::lock_guard lock(mutex_);
    return error_;
}

void LodWorker::run() {
    std::unique_lock lock(mutex_);
    for (;;) {
        wake_.wait(lock, [this] { return stop_ || pending_; });
        if (stop_)
            return;
        const View view = view_;
        const LodSettings settings = settings_;
        const std::uint64_t serial = request_serial_;
        pending_ = false;
        working_ = true;
        lock.unlock();
        std::unique_ptr<LodResult> result;
        std::string failure;
        try {
            result = engine_->compute(view, settings);
            result->serial = serial;
            result->view = view;
            result->settings = settings;
        } catch (const std::exception &e) {
            failure = e.what();
        }
        lock.lock();
        working_ = false;
        finished_serial_ = serial;
        if (result)
            result_ = std::move(result);
        error_ = failure;
        done_.notify_all();
    }
}

} // namespace tinlod::viewer
