// Unit tests of the refiner's internals (lib/src/refine), each against an exact computation
// written here: the motion bounds (motion_bounds.hpp) against screen_weight at both views, and
// ready_dependency (update.hpp) against a walk of the dependency graph of an erase's records.
#include "refine/motion_bounds.hpp"
#include "refine/update.hpp"
#include "tinlod/decimate.hpp"
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
// (a breadth-first walk of the records' graph), and the walk resumed from s.frame.chain returns
// what a walk from v alone returns.
TEST(ReadyDependency, ReturnsAReachableNodeWhoseRingIsLive) {
    const Heightfield hf = rough(33, 3);
    Mesh mesh = grid_tin(hf);
    EraseOptions options;
    options.tolerance = 12.0;
    options.shallow_history = true;
    NodeEraser eraser(mesh, Significance::vertical(), options);
    eraser.erase();

    const std::uint32_t nodes = std::uint32_t(mesh.n_vertices());
    EraserState s;
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
        s.frame.chain.clear();
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
            const std::uint32_t from_scratch = ready_dependency(fresh, v);

            const std::uint32_t x = ready_dependency(s, v);
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
