// What the erase tells a refiner that follows it (refine::FrameState implements it): the state the
// refiner's frame steps keep beside the eraser's, per live node (by its slot in LiveSet::list) and
// per face, is kept up by the erase's edits through these calls. A one-off erase has none
// (EraserState::follower is null): it neither carries nor maintains that state.
#pragma once

#include "erase/hole_geometry.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>

namespace tinlod::erase {

struct EraserState;
struct FaceIndex;

class Follower {
  public:
    virtual ~Follower() = default;
    // The input is read (Input, LiveSet::count), no node is live yet and the faces are the mesh's.
    virtual void started(const EraserState &s) = 0;
    // A node entered the live set in `slot` (the list's new last), at point p.
    virtual void live_added(std::uint32_t slot, const Mesh::Point &p) = 0;
    // The node in `slot` left the live set: the last slot moved into it and the list shrank.
    virtual void live_removed(std::uint32_t slot) = 0;
    // The node in `slot` turned dirty (its fan changed), or was parked (see park).
    virtual void dirtied(std::uint32_t slot) = 0;
    virtual void parked(std::uint32_t slot) = 0;
    // An evaluation of the node in `slot`: its SP so far is at least star_dev times the weight of
    // LiveNode::star, under any view, while its fan stands.
    virtual void evaluated(std::uint32_t slot, float star_dev) = 0;
    // The reach of the fan of the node in `slot`: its swallowed nodes lie within it (3-D).
    virtual float reach(std::uint32_t slot) const = 0;
    // Face f's swallowed nodes changed (or its list's order); a face was added to the mesh's
    // arrays (the last); the faces were compacted to `faces`.
    virtual void face_changed(FH f) = 0;
    virtual void face_added() = 0;
    virtual void faces_compacted(std::size_t faces) = 0;
    // The fans of the live nodes among the points p[0..count) (node ids `ids`) now hold the
    // triangles tri[0..ntri) over those points, whose swallowed nodes deviate at most dev[t].
    virtual void fans_widened(const EraserState &s, const glm::dvec3 *p, const std::uint32_t *ids,
                              int count, const RingTriangle *tri, const float *dev, int ntri) = 0;
    // The erase of node x, hole h, is about to take its fan faces face[0..fans) (in ring order)
    // and what they hold; node x's re-insert made them again: restores what they held then into
    // `faces` if the follower kept it, and says whether it did.
    virtual void fan_erasing(const EraserState &s, std::uint32_t x, const Hole &h, const FH *face,
                             int fans) = 0;
    virtual bool fan_restoring(FaceIndex &faces, std::uint32_t x, const FH *face, int fans) = 0;
    // An erase() begins; it ended (the live list may have shrunk to fit); a new model and view.
    virtual void erasing() = 0;
    virtual void erased(bool shrunk) = 0;
    virtual void view_changed() = 0;
};

} // namespace tinlod::erase
