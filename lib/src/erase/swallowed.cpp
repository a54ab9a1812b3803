// The swallowed lists and the fan bounds an edit widens (swallowed.hpp).
#include "erase/swallowed.hpp"

namespace tinlod::erase {

void widen_fans(EraserState &s, const glm::dvec3 *p, const std::uint32_t *ids, int count,
                const RingTriangle *tri, const float *dev, int ntri) {
    if (s.fans_stale)
        return;
    std::array<double, k_max_ring + 1> far2;
    std::array<float, k_max_ring + 1> most;
    std::fill_n(far2.begin(), count, 0.0);
    std::fill_n(most.begin(), count, 0.0f);
    for (int t = 0; t < ntri; ++t) {
        const std::uint8_t c[3] = {tri[t].a, tri[t].b, tri[t].c};
        for (int k = 0; k < 3; ++k) {
            const std::uint8_t i = c[k];
            for (int j = 1; j < 3; ++j) {
                const glm::dvec3 d = p[c[(k + j) % 3]] - p[i];
                far2[i] = std::max(far2[i], glm::dot(d, d));
            }
            most[i] = std::max(most[i], dev[t]);
        }
    }
    for (int i = 0; i < count; ++i) {
        if (s.record_of[ids[i]] >= 0)
            continue;
        LiveNode &l = live_node(s, ids[i]);
        l.seen_log = INFINITY;
        l.fan_exact = false;
        l.reach = std::max(l.reach, float_up(std::sqrt(far2[i]) + double(most[i])));
        l.fan_dev = std::max(l.fan_dev, most[i]);
        Cell &cell = s.cells[l.cell];
        cell.reach = std::max(cell.reach, l.reach);
        cell.fan_dev = std::max(cell.fan_dev, l.fan_dev);
    }
}

void unlink_swallowed(EraserState &s, std::int32_t f, std::uint32_t u) {
    std::int32_t *link = &s.face_head[std::size_t(f)];
    while (*link != std::int32_t(u))
        link = &s.next_swallowed[std::size_t(*link)];
    *link = s.next_swallowed[u];
    face_changed(s, FH(f)); // its blocks are runs of the list
}

} // namespace tinlod::erase
