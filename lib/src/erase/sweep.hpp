// The erase's drivers: the sweep (passes over the nodes in storage order, in rungs of rising
// limits), and the queue of the paper model.
#pragma once

#include "erase/state.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tinlod::erase {

// rank: every erasable node enters the queue keyed by the cost of its erase.
void rank_nodes(EraserState &s);

// erase: pops the least significant node while its erase stays within the tolerance.
std::int64_t erase_loop(EraserState &s);

// The input nodes the xy fan of x covers, estimated by its area at the input's mean density (low
// where the input does not fill its box).
double covered_estimate(const EraserState &s, std::uint32_t x);

// The sweep over the nodes of `list` only, then over the rings their erases changed, at `limit`
// alone, until `stop_at` live nodes remain: its cost follows the nodes that changed (an update's
// rungs below the limit cost time for no fewer nodes: docs/decisions/013-sweep.md). Fans over
// `cap` swallowed nodes are left as they are (see sweep_node). Returns the erases made.
std::int64_t sweep_dirty(EraserState &s, double limit, std::vector<std::uint32_t> list,
                         std::size_t cap, std::int64_t stop_at = 0);

// classify -> erase: SP models whose key is the cost (not `paper`), see the sweep above.
std::int64_t sweep_erase(EraserState &s);

} // namespace tinlod::erase
