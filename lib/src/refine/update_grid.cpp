// The update's grid and huge pages (update_grid.hpp).
#include "refine/update_grid.hpp"

#include "tinlod/util.hpp"

#include <algorithm>
#include <cmath>

namespace tinlod::refine {

using namespace erase;

void regrid(UpdateGrid &grid, std::vector<FanBounds> &fans, std::int64_t live) {
    const glm::dvec2 extent = grid.grid_hi - grid.grid_lo;
    const double cells = std::max(1.0, double(live) / k_live_per_cell);
    const double area = extent.x * extent.y;
    grid.cell_side = std::max(
        {area > 0.0 ? std::sqrt(area / cells) : 0.0, std::max(extent.x, extent.y) / 4000.0, 1e-30});
    grid.grid_nx = int(extent.x / grid.cell_side) + 1;
    grid.grid_ny = int(extent.y / grid.cell_side) + 1;
    grid.grid_live = live;
    grid.cells.assign(std::size_t(grid.grid_nx) * std::size_t(grid.grid_ny), Cell{});
    for (FanBounds &l : fans) {
        const glm::dvec3 p = to_glm(l.p);
        l.cell = cell_of(grid, p);
        Cell &cell = grid.cells[l.cell];
        cell.zlo = std::min(cell.zlo, float_down(p.z));
        cell.zhi = std::max(cell.zhi, float_up(p.z));
        cell.fan_dev = std::max(cell.fan_dev, l.fan_dev);
        cell.reach = std::max(cell.reach, l.reach);
    }
}

void advise_huge(const EraserState &s, FrameState &frame) {
    const Mesh &m = *s.input.mesh;
    frame.advised = {m.n_vertices() > 0 ? m.points() : nullptr,
                     m.n_edges() > 0 ? &m.edge(EH(0)) : nullptr,
                     m.n_faces() > 0 ? &m.face(FH(0)) : nullptr};
    if (m.n_vertices() > 0) {
        // Over the reserved room: the vertices that enter fill it.
        const std::size_t room = m.property(m.points_pph()).data_vector().capacity();
        advise_huge_pages(m.points(), room * sizeof(Mesh::Point));
        advise_huge_pages(&m.vertex(VH(0)), room * sizeof(m.vertex(VH(0))));
        advise_huge_pages(&m.status(VH(0)), room * sizeof(m.status(VH(0))));
    }
    if (m.n_edges() > 0)
        advise_huge_pages(&m.edge(EH(0)), m.n_edges() * sizeof(m.edge(EH(0))));
    if (m.n_faces() > 0)
        advise_huge_pages(&m.face(FH(0)), m.n_faces() * sizeof(m.face(FH(0))));
    if (s.input.lattice)
        advise_huge_pages(s.input.lattice->z.data(), s.input.lattice->z.size() * sizeof(float));
    const auto whole = [](const auto &v) { advise_huge_pages(v.data(), v.size() * sizeof(v[0])); };
    whole(s.history.record_of);
    whole(s.input.sample_of);
    whole(s.live.flags);
    whole(s.live.stamp);
    whole(s.weights.per_vertex);
    whole(s.faces.next_swallowed);
    whole(s.faces.face_head);
    whole(s.faces.face_maxdev);
}

} // namespace tinlod::refine
