// The refiner (refine.hpp): an eraser kept alive between frames with the refiner's state beside
// it (refine::Engine), moved view to view.
#include "tinlod/refine.hpp"

#include "refine/update.hpp"
#include "tinlod/error.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/util.hpp"

#include <cassert>

namespace tinlod {

namespace refine {

struct RefinerState {
    std::unique_ptr<Mesh> mesh;
    RefineOptions options;
    std::unique_ptr<Engine> engine;
    const Heightfield *lattice = nullptr; // the grid a heightfield's TIN holds samples of
    FrameStats first;
};

} // namespace refine

using refine::Engine;
using refine::RefinerState;

static EraseOptions erase_options(const RefineOptions &options, const Heightfield *lattice) {
    EraseOptions eo;
    eo.lattice = lattice;
    eo.tolerance = options.tolerance * (1.0 - options.hysteresis);
    eo.max_valence = options.max_valence;
    return eo;
}

// `retrieval`: the mesh is the quad-tree retrieval's TIN (HistoryOptions::retrieval_tin).
static erase::HistoryOptions history_options(bool retrieval) {
    erase::HistoryOptions ho;
    ho.shallow_history = true; // a recover must not undo a whole row of erases
    ho.absent_history = true;
    ho.retrieval_tin = retrieval;
    return ho;
}

static void start(RefinerState &s, const View &first, bool retrieval) {
    assert(s.options.tolerance > 0 && s.options.hysteresis >= 0 && s.options.hysteresis < 1);
    if (s.options.model == SpModel::vertical)
        throw Error("RefineOptions::model", "must be screen or paper: the refiner follows a view");
    Stopwatch clock;
    s.engine = std::make_unique<Engine>(
        *s.mesh, Significance::of(s.options.model, first, s.options.significance),
        erase_options(s.options, s.lattice), history_options(retrieval));
    NodeEraser &eraser = s.engine->eraser;
    const double weights_ms = clock.ms();
    clock.reset();
    const EraseStats e = eraser.erase();
    // The grid's erased edges and faces leave memory (a copy gets arrays of the compacted size),
    // with room for the TIN to grow by half before its arrays reallocate (and, from a heightfield,
    // for as many samples again as it has live nodes to enter).
    s.engine->compact();
    auto compacted = std::make_unique<Mesh>(*s.mesh);
    compacted->reserve(compacted->n_vertices() +
                           (s.lattice ? std::size_t(eraser.live_nodes()) : std::size_t(0)),
                       compacted->n_edges() * 3 / 2, compacted->n_faces() * 3 / 2);
    s.engine->rebind(*compacted);
    s.mesh = std::move(compacted);
    // An update from the same view makes the bounds that later updates carry over (each fan's and
    // face's weighted deviation, each node's least cost), so the first move does not pay for
    // them all at once.
    const UpdateStats warm = s.engine->update(first, s.options.tolerance,
                                              s.options.tolerance * (1.0 - s.options.hysteresis));
    UpdateStats &first_update = s.first.update;
    first_update.weights_ms = weights_ms;
    first_update.erase_ms = clock.ms();
    first_update.erased = e.erased + warm.erased;
    first_update.recovered = warm.recovered;
    first_update.candidates = e.evaluations;
    s.first.nodes = eraser.live_nodes();
    s.first.triangles = eraser.live_triangles();
    s.first.bound_px = e.max_weighted;
    s.first.total_ms = s.first.retrieve_ms + weights_ms + first_update.erase_ms;
}

// Starts from the TIN `retrieved(options)` gives, the quad-tree retrieval at the first retrieval's
// share of the erase tolerance (`retrieved` holds its quad-tree only while it runs, so the tree
// leaves memory before the erase), or from the full grid when the options ask for no retrieval
// (a 0 share, or a model other than the screen one).
template <class Retrieved>
static void start_on_grid(RefinerState &s, const Heightfield &hf, const View &first,
                          Retrieved retrieved) {
    const Stopwatch clock;
    const double share = s.options.model == SpModel::screen ? s.options.retrieve_share : 0;
    if (share > 0) {
        RetrieveOptions ro;
        ro.tolerance = share * s.options.tolerance * (1.0 - s.options.hysteresis);
        ro.peripheral = &s.options.significance;
        s.mesh = std::make_unique<Mesh>(retrieved(ro));
        s.first.retrieve_ms = clock.ms();
    } else {
        s.mesh = std::make_unique<Mesh>(grid_tin(hf));
    }
    s.lattice = &hf;
    start(s, first, share > 0);
}

Refiner::Refiner(const Heightfield &hf, const View &first, const RefineOptions &options)
    : state_(std::make_unique<RefinerState>()) {
    state_->options = options;
    start_on_grid(*state_, hf, first, [&](const RetrieveOptions &ro) {
        const QuadTree tree(hf);
        return to_sparse_lattice_mesh(retrieve(tree, first, ro), hf);
    });
}

Refiner::Refiner(const Heightfield &hf, std::unique_ptr<NodeSource> tree, const View &first,
                 const RefineOptions &options)
    : state_(std::make_unique<RefinerState>()) {
    assert(tree->frame().width == hf.width && tree->frame().height == hf.height);
    state_->options = options;
    start_on_grid(*state_, hf, first, [&](const RetrieveOptions &ro) {
        QuadTreeLod lod(std::move(tree));
        return to_sparse_lattice_mesh(lod.retrieve(first, ro), hf);
    });
}

Refiner::Refiner(Mesh mesh, const View &first, const RefineOptions &options)
    : state_(std::make_unique<RefinerState>()) {
    state_->mesh = std::make_unique<Mesh>(std::move(mesh));
    state_->options = options;
    start(*state_, first, false);
}

Refiner::~Refiner() = default;

const FrameStats &Refiner::first_frame() const { return state_->first; }

FrameStats Refiner::update(const View &view) {
    RefinerState &s = *state_;
    Stopwatch clock;
    const UpdateStats u = s.engine->update(view, s.options.tolerance,
                                           s.options.tolerance * (1.0 - s.options.hysteresis));
    FrameStats f;
    f.update = u;
    f.nodes = s.engine->eraser.live_nodes();
    f.triangles = s.engine->eraser.live_triangles();
    f.total_ms = clock.ms();
    return f;
}

const Mesh &Refiner::mesh() const { return *state_->mesh; }

bool Refiner::is_erased(Mesh::VertexHandle v) const { return state_->engine->eraser.is_erased(v); }

std::size_t Refiner::bytes() const {
    const Mesh &m = *state_->mesh;
    // OpenMesh's arrays, each entry as large as the mesh's types make it (a malloc count of the
    // mesh's copy agrees): per vertex a point, its item (an outgoing halfedge), a status word (4
    // bytes, not 1), the traits' data (an empty struct, still a byte) and the origin property if
    // it has one; per edge its two halfedges (vertex, next,
    // prev and face each), a status word and the traits' data of the edge and of its halfedges;
    // per face its item (a halfedge), a status word and the traits' data. Each array counts its
    // capacity, the status array's: every array of an element kind is reserved and grows with it.
    const Mesh::VertexHandle v(0);
    const Mesh::EdgeHandle e(0);
    const Mesh::FaceHandle f(0);
    const std::size_t origin = find_origin_property(m).is_valid() ? sizeof(std::int64_t) : 0;
    const std::size_t per_vertex = sizeof(m.point(v)) + sizeof(m.vertex(v)) + sizeof(m.status(v)) +
                                   sizeof(Mesh::VertexData) + origin;
    const std::size_t per_edge = sizeof(m.edge(e)) + sizeof(m.status(e)) + sizeof(Mesh::EdgeData) +
                                 2 * sizeof(Mesh::HalfedgeData);
    const std::size_t per_face = sizeof(m.face(f)) + sizeof(m.status(f)) + sizeof(Mesh::FaceData);
    const std::size_t mesh_bytes =
        m.property(m.vertex_status_pph()).data_vector().capacity() * per_vertex +
        m.property(m.edge_status_pph()).data_vector().capacity() * per_edge +
        m.property(m.face_status_pph()).data_vector().capacity() * per_face;
    return mesh_bytes + state_->engine->bytes();
}

} // namespace tinlod
