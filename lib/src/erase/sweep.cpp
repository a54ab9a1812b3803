// The sweep and the queue (sweep.hpp).
#include "erase/sweep.hpp"

#include "erase/edits.hpp"
#include "erase/erase_cost.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace tinlod::erase {

void rank_nodes(EraserState &s) {
    s.live.heap.reset(s.input.nodes);
    std::vector<std::uint32_t> ranked;
    ranked.reserve(std::size_t(s.live.count));
    for (auto v : s.input.mesh->vertices()) {
        const std::uint32_t x = node_of(s, v);
        if (s.live.flags[x] & k_locked)
            continue;
        s.live.flags[x] &= std::uint8_t(~k_dirty);
        const bool erasable = evaluate(s, v, s.input.options.tolerance);
        s.live.heap.store_key(x, erasable ? key_of(s, s.scratch.hole) : INFINITY);
        if (erasable)
            ranked.push_back(x);
    }
    s.live.heap.build(std::move(ranked));
}

namespace {

// The cost an erase may reach: the tolerance less a hair that keeps float rounding inside it.
static double erase_limit(const EraserState &s) { return s.input.options.tolerance * (1.0 - 1e-6); }

// After an erase its ring nodes' keys are stale: they are marked dirty (re-evaluated when they
// reach the top of the queue) and re-enter the queue if a failed evaluation had dropped them.
static void touch_ring(EraserState &s) {
    const Hole &h = s.scratch.hole;
    for (int i = 0; i < h.n; ++i) {
        const std::uint32_t u = node_of(s, h.r[i]);
        if (s.live.flags[u] & k_locked)
            continue;
        mark_dirty(s, u);
        if (!s.live.heap.contains(u))
            s.live.heap.set(u, float(std::min<double>(s.live.heap.key(u), erase_limit(s))));
    }
}

} // namespace

std::int64_t erase_loop(EraserState &s) {
    const double tau = erase_limit(s);
    const std::int64_t budget = std::max<std::int64_t>(s.input.options.max_nodes, 3);
    std::int64_t erased = 0;
    while (!s.live.heap.empty() && s.live.count > budget) {
        const std::uint32_t v = s.live.heap.top();
        const float key = s.live.heap.key(v);
        if (double(key) > tau && s.weights.model != SpModel::paper)
            break; // every remaining key exceeds the bound (dirty keys are re-checked below)
        const bool dirty = s.live.flags[v] & k_dirty;
        s.live.flags[v] &= std::uint8_t(~k_dirty);
        // A dirty node is erased only if its cost is still the least: its evaluation stops once
        // the cost passes the next key, and it goes back with that lower bound as its key, dirty
        // (the keys stay lower bounds of the costs, so the order is the one exact keys give),
        // not scanned whole (docs/decisions/013-sweep.md).
        const double second = double(s.live.heap.second_key());
        const bool by_cost = s.weights.model != SpModel::paper;
        bool erasable = evaluate(s, vh(s, v), dirty && by_cost ? std::min(tau, second) : tau);
        if (erasable && dirty && by_cost && second < tau && s.scratch.hole.sp > second) {
            if (float(s.scratch.hole.sp) > float(second)) {
                s.live.heap.set(v, float(s.scratch.hole.sp));
                s.live.flags[v] |= k_dirty;
                continue;
            }
            erasable = evaluate(s, vh(s, v), tau); // equal as floats: the exact cost decides
        }
        if (!erasable || !(s.scratch.hole.sp <= tau)) {
            s.live.heap
                .pop(); // cannot be erased now; touch_ring brings it back when its ring changes
            s.live.heap.store_key(v, erasable ? float(s.scratch.hole.sp) : INFINITY);
            continue;
        }
        const float fresh = key_of(s, s.scratch.hole);
        if (dirty && fresh > key && fresh > s.live.heap.second_key()) {
            s.live.heap.set(v, fresh); // its cost rose past another node's since it was ranked
            continue;
        }
        s.live.heap.pop();
        retriangulate(s);
        touch_ring(s);
        ++erased;
    }
    return erased;
}

namespace {

static double tau_rung_ratio(const EraserState &s) {
    return s.input.history.shallow_history ? k_history_rung_ratio : k_tau_rung_ratio;
}

static int tau_rungs(const EraserState &s) {
    if (s.input.history.shallow_history)
        return int(std::ceil(std::log(k_history_rung_floor) / std::log(k_history_rung_ratio)));
    return s.input.grid_w > 0 ? 0 : 1;
}

// A new sweep pass: its number in s.live.pass, the stamps of 256 passes ago cleared.
static void next_pass(EraserState &s) {
    if (++s.live.pass == 0) {
        if (s.live.node_keys)
            std::fill(s.live.slot_stamp.begin(), s.live.slot_stamp.end(), std::uint8_t(0));
        else
            std::fill(s.live.stamp.begin(), s.live.stamp.end(), std::uint8_t(0));
        s.live.pass = 1;
    }
    s.live.chain_cap = std::size_t(double(k_chain_swallowed) * double(s.input.nodes) /
                                   double(std::max<std::int64_t>(s.live.count, 1)));
}

} // namespace

double covered_estimate(const EraserState &s, std::uint32_t x) {
    const Mesh &m = *s.input.mesh;
    const VH v = vh(s, x);
    const glm::dvec2 c(to_glm(m.point(v)));
    double twice = 0.0;
    for (const HH he : m.voh_range(v)) {
        if (m.is_boundary(he))
            continue;
        const VH a = m.to_vertex_handle(he), b = m.to_vertex_handle(m.next_halfedge_handle(he));
        twice += orient(c, glm::dvec2(to_glm(m.point(a))), glm::dvec2(to_glm(m.point(b))));
    }
    return 0.5 * twice / s.input.area_per_node;
}

namespace {

// Leaves x as it is (not dirty, infinite key) until a change of its ring marks it dirty again.
static void park(EraserState &s, std::uint32_t x) {
    s.live.flags[x] &= std::uint8_t(~k_dirty);
    store_node_key(s, x, INFINITY);
    if (s.follower)
        s.follower->parked(live_slot(s, x));
}

// One step of a sweep at `limit` on live, unlocked node x: evaluates it and erases it when its
// cost is within the limit; a node whose fan swallowed more than `cap` nodes is left as it is
// until its ring changes. s.live.stamp holds, per node, the pass (mod 256) in which its ring last
// changed. Returns true when x was erased; x stays dirty when it must wait for the next pass.
// `observer` (may be null): see sweep_dirty.
static bool sweep_node(EraserState &s, std::uint32_t x, double limit,
                       std::size_t cap = std::numeric_limits<std::size_t>::max(),
                       SweepObserver *observer = nullptr) {
    // A node whose ring this pass changed waits for the next pass when its fan swallowed more
    // than s.live.chain_cap nodes (else a run of erases along a row, as on a flat sea where every
    // cost is 0, drags one growing face's nodes from erase to erase, quadratic in the run's
    // length), and always with a shallow history.
    const bool fresh = node_stamp(s, x) == s.live.pass;
    if (fresh && s.input.history.shallow_history)
        return false;
    // Over the cap by its area: left as it is without locating the first `cap` nodes
    // (docs/decisions/015-chain-and-update-caps.md). The fan lies in the disc of its reach (an
    // follower keeps the live nodes' fan bounds), so most fans need no walk to pass.
    const auto over_cap = [&] {
        const double reach = double(s.follower->reach(live_slot(s, x)));
        return M_PI * reach * reach > double(cap) * s.input.area_per_node &&
               covered_estimate(s, x) > double(cap);
    };
    if (cap != std::numeric_limits<std::size_t>::max() && s.input.xy &&
        s.input.area_per_node > 0.0 && over_cap()) {
        park(s, x);
        return false;
    }
    if (!evaluate(s, vh(s, x), limit, fresh ? std::min(cap, s.live.chain_cap) : cap)) {
        park(s, x);
        return false;
    }
    if (s.scratch.hole.deferred) {
        if (!fresh)
            park(s, x); // over the cap
        return false;
    }
    s.live.flags[x] &= std::uint8_t(~k_dirty);
    if (!(s.scratch.hole.sp <= limit)) {
        store_node_key(s, x, float(s.scratch.hole.sp));
        if (observer)
            observer->too_costly(live_slot(s, x), s.scratch.hole.sp);
        return false;
    }
    if (observer)
        observer->erasing(x, s.scratch.hole);
    retriangulate(s);
    if (observer)
        observer->erased(s.scratch.hole);
    for (int i = 0; i < s.scratch.hole.n; ++i) {
        mark_dirty(s, node_of(s, s.scratch.hole.r[i]));
        node_stamp(s, node_of(s, s.scratch.hole.r[i])) = s.live.pass;
    }
    return true;
}

// One pass at `limit` over the nodes of `order` (ascending ids, those that were live and not locked
// when the erase began), until `stop_at` live nodes remain. Drops from `order` the nodes it finds
// erased: a pass costs the nodes still live, not the input's (the refiner's first erase makes
// dozens of passes; docs/decisions/013-sweep.md).
static std::int64_t sweep_pass(EraserState &s, std::vector<std::uint32_t> &order, double limit,
                               std::int64_t stop_at, const std::function<void(double)> &report) {
    next_pass(s);
    std::int64_t erased = 0;
    std::size_t kept = 0, i = 0;
    for (; i < order.size() && s.live.count > stop_at; ++i) {
        if (report && i % 4096 == 0)
            report(double(i) / double(order.size()));
        const std::uint32_t x = order[i];
        if (s.history.record_of[x] >= 0)
            continue;
        order[kept++] = x;
        if (!(s.live.flags[x] & k_dirty) && double(node_key(s, x)) > limit)
            continue;
        erased += sweep_node(s, x, limit);
    }
    for (; i < order.size(); ++i)
        order[kept++] = order[i];
    order.resize(kept);
    return erased;
}

} // namespace

std::int64_t sweep_dirty(EraserState &s, double limit, std::vector<std::uint32_t> list,
                         std::size_t cap, std::int64_t stop_at, SweepObserver *observer) {
    std::int64_t erased = 0;
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    while (!list.empty() && s.live.count > stop_at) {
        next_pass(s);
        std::vector<std::uint32_t> next;
        for (const std::uint32_t x : list) {
            if (s.live.count <= stop_at)
                break;
            if ((s.live.flags[x] & k_locked) || s.history.record_of[x] >= 0)
                continue;
            if (!(s.live.flags[x] & k_dirty) && double(node_key(s, x)) > limit)
                continue;
            if (sweep_node(s, x, limit, cap, observer)) {
                ++erased;
                for (int i = 0; i < s.scratch.hole.n; ++i)
                    next.push_back(node_of(s, s.scratch.hole.r[i]));
            } else if (s.live.flags[x] & k_dirty) {
                next.push_back(x); // waits for the next pass
            }
        }
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        list = std::move(next);
    }
    return erased;
}

namespace {

// The fine rungs of a node budget, until `budget` live nodes remain or a rung reaches `tau`: the
// first at `limit` (it finishes the coarse rung the budget's first stop cut short), each next one
// k_fine_rung_ratio above the last, or at the least key above it when that is higher. A rung sweeps
// the dirty nodes and those whose key it covers, then the rings their erases change, until none is
// left: afterwards every live node's key (a lower bound of its cost) is above the rung. Returns the
// erases made.
static std::int64_t fine_rungs(EraserState &s, double limit, double tau, std::int64_t budget,
                               const std::function<void()> &report) {
    std::int64_t erased = 0;
    limit = std::min(limit, tau);
    while (s.live.count > budget) {
        if (report)
            report();
        std::vector<std::uint32_t> list;
        for (std::uint32_t i = 0; i < std::uint32_t(s.live.list.size()); ++i) {
            const std::uint32_t x = s.live.list[i].node;
            if (!(s.live.flags[x] & k_locked) &&
                ((s.live.flags[x] & k_dirty) || double(node_key(s.live, i)) <= limit))
                list.push_back(x);
        }
        erased +=
            sweep_dirty(s, limit, std::move(list), std::numeric_limits<std::size_t>::max(), budget);
        if (limit >= tau)
            break;
        double least = INFINITY;
        for (std::uint32_t i = 0; i < std::uint32_t(s.live.list.size()); ++i)
            if (!(s.live.flags[s.live.list[i].node] & k_locked))
                least = std::min(least, double(node_key(s.live, i)));
        if (!(least < INFINITY))
            break; // no live node can be erased
        limit = std::min(tau, std::max(limit * k_fine_rung_ratio, least));
    }
    return erased;
}

} // namespace

namespace {

// The nodes a sweep visits, in ascending ids: the live, unlocked ones. Their keys are reset (0
// until a node is first measured) and none is dirty.
std::vector<std::uint32_t> sweep_order(EraserState &s) {
    s.live.heap.reset(s.input.nodes); // keys only
    for (auto v : s.input.mesh->vertices())
        s.live.flags[node_of(s, v)] &= std::uint8_t(~k_dirty);
    std::vector<std::uint32_t> order;
    order.reserve(std::size_t(s.live.count));
    for (std::uint32_t x = 0; x < s.input.nodes; ++x)
        if (!(s.live.flags[x] & k_locked) && s.history.record_of[x] < 0)
            order.push_back(x);
    return order;
}

// EraseOptions::progress for a sweep: with a budget, the erases made over those it needs; with a
// bound alone, pass k (from 0) spans [1 - 0.1^k, 1 - 0.1^(k+1)).
class SweepProgress {
  public:
    SweepProgress(const EraserState &s, std::int64_t budget)
        : s_(s), progress_(s.input.options.progress), budget_(budget), first_live_(s.live.count) {}
    // The report within a pass (null without a progress callback), and the step to the next pass.
    std::function<void(double)> within_pass() {
        if (!progress_)
            return nullptr;
        return [this](double within) {
            if (s_.input.options.max_nodes > 0)
                by_erases();
            else
                progress_(1.0 - pass_share_ + 0.9 * pass_share_ * within);
        };
    }
    void next_pass() { pass_share_ *= 0.1; }
    // The report by erases made (null without a progress callback), for the fine rungs.
    std::function<void()> erases() {
        if (!progress_)
            return nullptr;
        return [this] { by_erases(); };
    }

  private:
    void by_erases() const {
        progress_(first_live_ > budget_ ? std::clamp(double(first_live_ - s_.live.count) /
                                                         double(first_live_ - budget_),
                                                     0.0, 1.0)
                                        : 1.0);
    }
    const EraserState &s_;
    const std::function<void(double)> &progress_;
    std::int64_t budget_, first_live_;
    double pass_share_ = 1.0;
};

// One pass of the sweep at `limit` (sweep_pass), reported.
std::int64_t sweep(EraserState &s, std::vector<std::uint32_t> &order, double limit,
                   std::int64_t stop_at, SweepProgress &progress) {
    const std::int64_t made = sweep_pass(s, order, limit, stop_at, progress.within_pass());
    progress.next_pass();
    return made;
}

// A bound alone: the passes at tau / ratio^k, k = tau_rungs(s) .. 1, then passes at tau until one
// erases nothing. Returns the erases made.
std::int64_t tolerance_passes(EraserState &s, std::vector<std::uint32_t> &order, double tau,
                              SweepProgress &progress) {
    std::int64_t erased = 0;
    for (int rung = tau_rungs(s); rung > 0; --rung)
        erased += sweep(s, order, tau * std::pow(tau_rung_ratio(s), -rung), 0, progress);
    for (std::int64_t made = 1; made > 0;) {
        made = sweep(s, order, tau, 0, progress);
        erased += made;
    }
    return erased;
}

// The coarse rungs of a budget and the limit of the last (0 when none ran).
struct CoarseRungs {
    std::int64_t erased = 0;
    double limit = 0.0;
};

// A budget's coarse rungs, one pass each at limits k_budget_rung_ratio apart, until `far` live
// nodes remain or a rung reaches tau. The first rung: at least live - far erases are needed before
// the fine rungs, and an erase rarely costs less than the node's cost on the input, so the
// (live - far)-th smallest first cost (estimated on every k_sample_stride-th node) is about the
// least bound the output can reach; rungs below it only add passes.
CoarseRungs coarse_rungs(EraserState &s, std::vector<std::uint32_t> &order, double tau,
                         std::int64_t far, SweepProgress &progress) {
    CoarseRungs out;
    if (!(s.live.count > far))
        return out;
    std::vector<float> costs;
    for (std::uint32_t x = 0; x < s.input.nodes; x += k_sample_stride) {
        if ((s.live.flags[x] & k_locked) || s.history.record_of[x] >= 0)
            continue;
        const float cost = evaluate(s, vh(s, x), INFINITY) ? float(s.scratch.hole.sp) : INFINITY;
        s.live.heap.store_key(x, cost);
        costs.push_back(cost);
    }
    const auto nth =
        costs.begin() +
        std::ptrdiff_t(double(costs.size()) * double(s.live.count - far) / double(s.live.count));
    if (nth == costs.end())
        return out;
    std::nth_element(costs.begin(), nth, costs.end());
    double highest = 0.0;
    for (const float c : costs)
        if (std::isfinite(c))
            highest = std::max(highest, double(c));
    double &limit = out.limit;
    for (limit = std::max(double(*nth), 1e-30);
         s.live.count > far && limit < tau && limit <= 2.0 * highest; limit *= k_budget_rung_ratio)
        out.erased += sweep(s, order, limit, far, progress);
    limit /= k_budget_rung_ratio;
    return out;
}

} // namespace

std::int64_t sweep_erase(EraserState &s) {
    const double tau = erase_limit(s);
    std::vector<std::uint32_t> order = sweep_order(s);
    const std::int64_t budget = std::max<std::int64_t>(s.input.options.max_nodes, 3);
    SweepProgress progress(s, budget);
    if (s.input.options.max_nodes <= 0)
        return tolerance_passes(s, order, tau, progress);
    const CoarseRungs coarse = coarse_rungs(s, order, tau, k_coarse_share * budget, progress);
    return coarse.erased + fine_rungs(s, coarse.limit, tau, budget, progress.erases());
}

} // namespace tinlod::erase
