// Unit tests of the refiner's internals (lib/src/refine), each against an exact computation
// written here: the motion bounds (motion_bounds.hpp) against screen_weight at both views, and
// ready_dependency (update.hpp) against a walk of the dependency graph of an erase's records. And
// the refiner's engine (refine::Engine) driven directly: compaction, and updates that keep the
// bound and leave no node they could erase.
#include "erase_fixtures.hpp"

#include "refine/motion_bounds.hpp"
#include "refine/update.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/significance.hpp"
#include "tinlod/tin.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

using namespace tinlod;
using namespace tinlod::erase;
using namespace tinlod::refine;

namespace {

glm::dvec3 random_unit(std::mt19937 &rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    for (;;) {
        const glm::dvec3 d(n(rng), n(rng), n(rng));
        if (glm::length(d) > 1e-3)
            return glm::normalize(d);
    }
}

// The eye's move and the axis's turn from `then` to `now`, as the update measures them.
refine::ViewBounds::Since since_views(const View &then, const View &now) {
    refine::ViewBounds::Since d;
    d.moved = glm::length(now.eye - then.eye);
    d.turn = std::acos(std::clamp(glm::dot(then.axis(), now.axis()), -1.0, 1.0));
    d.ok = true;
    return d;
}

} // namespace

// For random pairs of views and points, the weight at the new view, computed exactly with
// screen_weight, is within the growth bounds times the weight at the old one, and at least the
// old one over the shrink bound; log_growth over-estimates the logarithm of weight_growth.
TEST(MotionBounds, BoundTheExactWeightAtBothViews) {
    std::mt19937 rng(47);
    std::uniform_real_distribution<double> unit(0.0, 1.0), coord(-1000.0, 1000.0);
    SignificanceOptions options;
    std::int64_t tested = 0, tight = 0;
    for (int trial = 0; trial < 200000; ++trial) {
        options.falloff_deg = 2.0 + 40.0 * unit(rng);
        options.floor = unit(rng) < 0.5 ? 0.02 : 0.3 * unit(rng);
        View then;
        then.eye = {coord(rng), coord(rng), coord(rng)};
        then.at = then.eye + random_unit(rng);
        then.fov_deg = 20.0 + 100.0 * unit(rng);
        View now = then;
        const double scale = std::pow(10.0, 3.0 * unit(rng));
        now.eye = then.eye + random_unit(rng) * unit(rng) * scale;
        // A small turn most of the time, as between frames, and any turn at times.
        const glm::dvec3 axis =
            unit(rng) < 0.8 ? glm::normalize(then.axis() + 0.2 * unit(rng) * random_unit(rng))
                            : random_unit(rng);
        now.at = now.eye + axis;
        const glm::dvec3 p = now.eye + random_unit(rng) * (scale * (0.5 + 20.0 * unit(rng)));
        const double w_then = screen_weight(then, p, options),
                     w_now = screen_weight(now, p, options);
        const refine::ViewBounds::Since d = since_views(then, now);
        EraserState s;
        s.weights.model = SpModel::screen;
        s.weights.significance = options;
        s.weights.weigher = Weigher(now, options);
        const double nearest = glm::length(p - now.eye);
        const bool cone_then = Weigher(then, options).in_cone(p, p),
                   cone_now = s.weights.weigher.in_cone(p, p);
        for (const bool cone : {false, true}) {
            // The `cone` bounds hold only for nodes in the cone of the view they name.
            if (cone && !cone_then && !cone_now)
                continue;
            const double growth = weight_growth(s.weights.weigher, d, nearest, cone);
            const double lg = log_growth(s.weights.weigher, d, nearest, cone),
                         ls = log_shrink(s.weights.weigher, d, nearest, cone);
            if (!std::isfinite(growth))
                continue;
            ++tested;
            if (!cone || cone_then) {
                EXPECT_LE(w_now, growth * w_then * (1.0 + 1e-12))
                    << "trial " << trial << " cone " << cone;
                EXPECT_GE(lg, std::log(growth) - 1e-12) << "trial " << trial << " cone " << cone;
                tight += w_now > 0.5 * growth * w_then;
            }
            if (!cone || cone_now) {
                EXPECT_GE(std::log(w_now), std::log(w_then) - ls - 1e-12)
                    << "trial " << trial << " cone " << cone;
            }
        }
    }
    EXPECT_GT(tested, 100000);
    EXPECT_GT(tight, 1000); // the bounds were not all far from the weights
}

// moved_within says yes only when, for every point within r of p, x = moved / its distance to the
// eye is at most 1/4 and slack > per_x x; checked at the nearest such point, which has the largest
// x.
TEST(MotionBounds, MovedWithinHoldsAtTheNearestPoint) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0), coord(-100.0, 100.0);
    std::int64_t yes = 0, no = 0;
    for (int trial = 0; trial < 200000; ++trial) {
        const glm::dvec3 eye(coord(rng), coord(rng), coord(rng)),
            p(coord(rng), coord(rng), coord(rng));
        const double r = 20.0 * unit(rng) * unit(rng), moved = 10.0 * unit(rng) * unit(rng);
        const double slack = 2.0 * unit(rng) - 0.2, per_x = 1.0 + 3.0 * unit(rng);
        if (!moved_within(eye, p, r, moved, slack, per_x)) {
            ++no;
            continue;
        }
        ++yes;
        const double nearest = glm::length(p - eye) - r;
        ASSERT_GT(nearest, 0.0) << "trial " << trial;
        const double x = moved / nearest;
        EXPECT_LE(x, 0.25) << "trial " << trial;
        EXPECT_GT(slack, per_x * x) << "trial " << trial;
    }
    EXPECT_GT(yes, 10000);
    EXPECT_GT(no, 10000);
}

namespace {

// A small grid TIN of rough random heights.
Heightfield rough(std::uint32_t side, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> z(0.0f, 30.0f);
    Heightfield hf;
    hf.width = hf.height = int(side);
    hf.dx = hf.dy = 10.0;
    hf.z.resize(std::size_t(side) * side);
    for (float &x : hf.z)
        x = z(rng);
    return hf;
}

} // namespace

// On a TIN erased with a shallow history, with its records copied into an EraserState from
// ring(): for every erased node v, re-inserting what ready_dependency returns until v is back
// always re-inserts an erased node whose ring is all live, reached from v along erased ring nodes
// (a breadth-first walk of the records' graph), and the walk resumed from FrameState::chain returns
// what a walk from v alone returns.
TEST(ReadyDependency, ReturnsAReachableNodeWhoseRingIsLive) {
    const Heightfield hf = rough(33, 3);
    Mesh mesh = grid_tin(hf);
    EraseOptions options;
    options.tolerance = 12.0;
    HistoryOptions history;
    history.shallow_history = true;
    NodeEraser eraser =
        EraserAccess::make(mesh, Significance::vertical(), options, history, nullptr);
    eraser.erase();

    const std::uint32_t nodes = std::uint32_t(mesh.n_vertices());
    EraserState s;
    FrameState frame;
    s.input.mesh = &mesh;
    s.input.nodes = nodes;
    s.input.xy = true;
    std::vector<std::vector<std::uint32_t>> rings(nodes);
    std::vector<std::int32_t> erased_record(nodes, -2); // the records as erased, kept
    std::vector<std::uint32_t> erased;
    for (std::uint32_t x = 0; x < nodes; ++x) {
        if (!eraser.is_erased(VH(int(x))))
            continue;
        erased.push_back(x);
        rings[x] = eraser.ring(VH(int(x))).nodes;
        EraseRecord record;
        record.ring_size = std::uint8_t(rings[x].size());
        record.ring_capacity = record.ring_size;
        record.ring_begin = std::uint32_t(s.history.ring_pool.append(rings[x].size()));
        for (std::size_t i = 0; i < rings[x].size(); ++i)
            s.history.ring_pool[record.ring_begin + i] = rings[x][i];
        erased_record[x] = std::int32_t(s.history.records.append(1));
        s.history.records[std::size_t(erased_record[x])] = record;
    }
    ASSERT_GT(erased.size(), nodes / 3);

    std::int64_t steps = 0, deep = 0;
    for (const std::uint32_t v : erased) {
        s.history.record_of = erased_record;
        frame.chain.clear();
        for (std::int64_t k = 0;; ++k) {
            ASSERT_LT(k, std::int64_t(erased.size()));
            // The nodes reachable from v along erased ring nodes, as they stand.
            std::set<std::uint32_t> reach = {v};
            std::vector<std::uint32_t> todo = {v};
            while (!todo.empty()) {
                const std::uint32_t at = todo.back();
                todo.pop_back();
                for (const std::uint32_t r : rings[at])
                    if (s.history.record_of[r] >= 0 && reach.insert(r).second)
                        todo.push_back(r);
            }
            EraserState fresh;
            fresh.input.mesh = s.input.mesh;
            fresh.input.xy = true;
            fresh.history.record_of = s.history.record_of;
            fresh.history.records = s.history.records;
            fresh.history.ring_pool = s.history.ring_pool;
            FrameState fresh_frame;
            const std::uint32_t from_scratch = ready_dependency(fresh, fresh_frame, v);

            const std::uint32_t x = ready_dependency(s, frame, v);
            ASSERT_GE(s.history.record_of[x], 0) << "node " << x << " for " << v << " is live";
            EXPECT_TRUE(reach.count(x)) << "node " << x << " is not reached from " << v;
            for (const std::uint32_t r : rings[x])
                EXPECT_LT(s.history.record_of[r], 0)
                    << "ring node " << r << " of " << x << " is erased";
            EXPECT_EQ(x, from_scratch) << "the resumed walk for " << v << " differs";
            ++steps;
            if (x == v)
                break;
            ++deep;
            s.history.record_of[x] = -2; // re-inserted: live
        }
    }
    EXPECT_GT(deep, 10); // some recoveries waited on others
    EXPECT_GE(steps, std::int64_t(erased.size()));
}

namespace {

using test::corner_view;
using test::CornerCrop;
using test::invariants;
using test::load_cropped;
using test::triangle_set;

} // namespace

// Without HistoryOptions::absent_history the samples a retrieval's TIN left out cannot enter:
// following a view is refused.
TEST(Engine, UpdateRefusesSamplesThatCannotEnter) {
    const Heightfield hf = load_cropped({"N42E001.hgt", false, 257});
    const View view = corner_view(hf);
    const Retrieval retrieval = retrieve(QuadTree(hf), view, {0.5, false});
    ASSERT_LT(retrieval.nodes.size(), std::size_t(hf.size()));
    Mesh work = to_lattice_mesh(retrieval, hf);
    Engine engine(work, Significance::screen(view), EraseOptions{}, {});
    EXPECT_GT(engine.eraser.erase().erased, 0);
    EXPECT_THROW(engine.update(view, 1.0, 0.75), std::logic_error);
}

// Engine::compact() drops the erased edges and faces; the history still recovers every node
// exactly, on a copy of the compacted mesh (rebind), with edges and faces created as the re-inserts
// need them.
TEST(Engine, CompactedHistoryRecoversExactly) {
    CornerCrop crop;
    const View &view = crop.view;
    Mesh &input = crop.input;
    const auto &input_triangles = crop.triangles;
    EraseOptions options;
    options.tolerance = 1.0;
    Mesh work = input;
    Engine engine(work, Significance::screen(view), options, {});
    NodeEraser &eraser = engine.eraser;
    const EraseStats stats = eraser.erase();
    ASSERT_GT(stats.erased, 1000);
    const auto erased_triangles = triangle_set(work);

    engine.compact();
    Mesh copy = work;
    engine.rebind(copy);
    EXPECT_EQ(std::int64_t(copy.n_faces()), eraser.live_triangles());
    EXPECT_EQ(copy.n_edges(), copy.n_faces() + copy.n_vertices() - std::size_t(stats.erased) - 1);
    EXPECT_EQ(copy.n_vertices(), input.n_vertices());
    EXPECT_EQ(triangle_set(copy), erased_triangles);
    EXPECT_LE(eraser.measure().max_weighted, options.tolerance);

    std::vector<int> nodes;
    for (auto v : input.vertices())
        if (eraser.is_erased(v))
            nodes.push_back(v.idx());
    std::mt19937 rng(11);
    std::shuffle(nodes.begin(), nodes.end(), rng);
    std::int64_t recovered = 0;
    for (std::size_t k = 0; k < nodes.size() / 4; ++k)
        recovered += eraser.recover(Mesh::VertexHandle(nodes[k]));
    Mesh partial = eraser.mesh();
    partial.garbage_collection();
    EXPECT_EQ(test::count_folded_faces(partial), 0);
    EXPECT_EQ(invariants(partial).non_manifold, 0);
    EXPECT_EQ(invariants(partial).euler, invariants(input).euler);

    EXPECT_EQ(recovered + eraser.recover_all(), stats.erased);
    Mesh back = eraser.mesh();
    back.garbage_collection();
    EXPECT_EQ(back.n_faces(), input.n_faces());
    EXPECT_EQ(triangle_set(back), input_triangles);
}

// After Engine::compact() an update keeps the live nodes' keys and sweep stamps with them; an
// erase() after that goes back to per-vertex ones. Both keep their bound, and every node still
// recovers.
TEST(Engine, UpdatesAfterCompactThenAnotherEraseKeepTheirBounds) {
    CornerCrop crop;
    const View &view = crop.view;
    View nearer = view;
    nearer.eye += 0.5 * (view.at - view.eye);
    EraseOptions options;
    options.tolerance = 0.75;
    Mesh work = crop.input;
    Engine engine(work, Significance::screen(view), options, {});
    NodeEraser &eraser = engine.eraser;
    eraser.erase();
    engine.compact();
    Mesh copy = work;
    engine.rebind(copy);
    for (const View &v : {nearer, view, nearer}) {
        const UpdateStats u = engine.update(v, 1.0, 0.75);
        EXPECT_GT(u.recovered + u.erased, 0);
        EXPECT_LE(eraser.measure().max_weighted, 1.0);
    }
    // From the last update's view (from another, what the TIN left coarse for that one may show
    // more than the bound: an erase cannot lower it).
    EraseOptions looser = options;
    looser.tolerance = 2.0;
    eraser.set_view(Significance::screen(nearer), looser);
    const EraseStats again = eraser.erase();
    EXPECT_GT(again.erased, 0);
    EXPECT_LE(again.max_weighted, 2.0);
    const UpdateStats u = engine.update(view, 2.0, 1.5);
    EXPECT_GT(u.recovered, 0);
    EXPECT_LE(eraser.measure().max_weighted, 2.0);
    eraser.recover_all();
    Mesh back = eraser.mesh();
    back.garbage_collection();
    EXPECT_EQ(triangle_set(back), crop.triangles);
}

// An update evaluates only the nodes whose cost may have fallen to its erase bound: the rest are
// left by bounds (their last cost carried to the new view, their worst node's deviation times its
// weight now, the grid's cells). If any of those bounds overstated a cost, a node the update should
// have erased would stay. After the updates of an approach, a retreat and a turn over a real DEM,
// every live node costs more than the erase bound, measured over all the nodes its hole would
// swallow, unless its fan covers more than an update takes on (k_update_cap). Overstating by 20-30
// % the motion shortcut's bound (moved_within), the worst node's or a cell's fails it.
TEST(Engine, UpdateLeavesNoNodeItCouldErase) {
    const Heightfield hf = load_cropped({"N42E001.hgt", false, 401});
    const View start = corner_view(hf);
    Mesh input = grid_tin(hf);
    EraseOptions options;
    options.tolerance = 1.0;
    Engine engine(input, Significance::screen(start), options, {});
    NodeEraser &eraser = engine.eraser;
    eraser.erase();
    engine.compact(); // as the refiner runs its updates
    Mesh work = input;
    engine.rebind(work);
    // Small steps, as a flight makes them: the bounds carried from frame to frame by the eye's move
    // have a shortcut for moves small against the distance.
    std::vector<View> views;
    for (int i = 1; i <= 40; ++i) {
        View v = start;
        v.eye += 0.025 * (i <= 20 ? i : 40 - i) * (start.at - start.eye);
        views.push_back(v);
    }
    for (int i = 1; i <= 8; ++i) {
        View v = start;
        v.at.x -= 0.05 * i * (hf.width - 1) * hf.dx;
        views.push_back(v);
    }
    constexpr double k_erase_below = 0.75;
    std::int64_t changed = 0, checked = 0, over_cap = 0;
    double least = INFINITY;
    for (std::size_t i = 0; i < views.size(); ++i) {
        const View &view = views[i];
        const UpdateStats u = engine.update(view, 1.0, k_erase_below);
        changed += u.erased + u.recovered;
        if (i % 4 != 3)
            continue; // every 4th update is checked (each check evaluates every live node)
        int erasable = 0;
        for (const auto v : eraser.mesh().vertices()) {
            if (eraser.is_erased(v))
                continue;
            const NodeEraser::Cost c = eraser.erase_cost(v);
            if (c.covered > double(k_update_cap)) {
                ++over_cap;
                continue;
            }
            ++checked;
            least = std::min(least, c.cost);
            erasable += !(c.cost > k_erase_below);
        }
        EXPECT_EQ(erasable, 0) << "eye " << view.eye.x << ", " << view.eye.y << ", " << view.eye.z;
    }
    // Not vacuous: the updates changed the TIN, and the nodes checked come close to the bound.
    EXPECT_GT(changed, 1000);
    EXPECT_GT(checked, 20 * over_cap);
    EXPECT_LT(least, 1.05 * k_erase_below);
}
