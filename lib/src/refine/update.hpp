// The refiner's engine: an eraser and the refiner's state that follows it, and its frame step,
// Engine::update(view, recover_above, erase_below), whose algorithm opens tinlod/refine.hpp.
#pragma once

#include "erase/state.hpp"
#include "refine/frame_state.hpp"

#include <cstddef>
#include <cstdint>

namespace tinlod::refine {

using erase::EraserState;

// An eraser made with the options only the refiner sets, and the refiner's state, which the
// erase's edits keep up (the eraser's follower, so an Engine does not move). The Refiner holds
// one; the tests of the internals drive one directly.
struct Engine {
    FrameState frame; // before eraser, which points to it
    NodeEraser eraser;

    Engine(Mesh &mesh, const Significance &model, const EraseOptions &options,
           const erase::HistoryOptions &history);
    Engine(const Engine &) = delete;
    Engine &operator=(const Engine &) = delete;

    EraserState &state() { return erase::EraserAccess::state(eraser); }
    const EraserState &state() const { return erase::EraserAccess::state(eraser); }

    // Follows the observer to `view` in both directions (the refiner's frame step):
    //  1. recover: every face whose swallowed nodes exceed `recover_above` (weighted, the units of
    //     the tolerance) under the new weights gets nodes back top down, until every face is
    //     within `recover_above`: the erase its worst node's recovery waits on (the first erased
    //     ring node down the chain of dependencies, or the node itself) is undone, and the face is
    //     checked again. Faces are found from the live nodes' bounds on their fans (reach and
    //     largest deviation), so only the fans those bounds cannot clear are walked;
    //  2. erase: the nodes just recovered, the nodes whose ring changed, and the live nodes whose
    //     last evaluation's worst node (its deviation times its weight now: a lower bound of the
    //     cost) no longer keeps them above `erase_below` are swept (passes over those nodes and
    //     the rings their erases change) and erased while their cost stays <= `erase_below`.
    // Its cost follows the live nodes (a few operations each) and the nodes that change, not the
    // input's size.
    // With erase_below < recover_above a node between the two keeps its state (hysteresis). After
    // the call the whole-output bound holds at `recover_above`: every swallowed node's weighted
    // deviation is <= recover_above. Needs a view (not SpModel::vertical). Throws std::logic_error
    // for a TIN with samples left out but no HistoryOptions::absent_history: they could not enter.
    UpdateStats update(const View &view, double recover_above, double erase_below);
    // erase::compact (history.hpp): the erased edges and faces leave the mesh's arrays.
    void compact();
    // Continues on `mesh`, a copy of the eraser's current mesh, for a long run of updates: the
    // large arrays (the mesh's and the eraser's) are moved to huge pages where the kernel allows,
    // and the bounds the updates keep on the live nodes' fans are built now (else the first update
    // after an erase() builds them).
    void rebind(Mesh &mesh);
    // Bytes held beside the mesh: the eraser's and the refiner's state.
    std::size_t bytes() const;
};

// The erased node to recover first on the way to erased node v: v, or the end of the chain of the
// erases v's recovery depends on, taking at each step the erased ring node nearest v (in xy for a
// TIN). The chain then stays over v, and each node recovered refines the faces around it (fewer
// recoveries than with the first erased ring node: docs/decisions/018-recovery-order.md).
// The chain is kept in frame.chain: the update asks again for the same v once the chain's end is
// back, and the nodes before the first one recovered since chose as they would now (a recovery
// only takes nodes out of their choice), so the walk resumes there instead of from v, which read
// each node's ring again per step.
std::uint32_t ready_dependency(const EraserState &s, FrameState &frame, std::uint32_t v);

} // namespace tinlod::refine
