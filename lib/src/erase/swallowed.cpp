// The swallowed lists and the fan bounds an edit widens (swallowed.hpp).
#include "erase/swallowed.hpp"

namespace tinlod::erase {

void unlink_swallowed(EraserState &s, std::int32_t f, std::uint32_t u) {
    std::int32_t *link = &s.face_head[std::size_t(f)];
    while (*link != std::int32_t(u))
        link = &s.next_swallowed[std::size_t(*link)];
    *link = s.next_swallowed[u];
    face_changed(s, FH(f)); // its blocks are runs of the list
}

} // namespace tinlod::erase
