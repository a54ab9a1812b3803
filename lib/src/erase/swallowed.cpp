// The swallowed lists (swallowed.hpp).
#include "erase/swallowed.hpp"

namespace tinlod::erase {

void unlink_swallowed(FaceIndex &faces, Follower *follower, std::int32_t f, std::uint32_t u) {
    std::int32_t *link = &faces.face_head[std::size_t(f)];
    while (*link != std::int32_t(u))
        link = &faces.next_swallowed[std::size_t(*link)];
    *link = faces.next_swallowed[u];
    face_changed(follower, FH(f)); // the follower's blocks are runs of the list
}

} // namespace tinlod::erase
