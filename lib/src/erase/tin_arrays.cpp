// Triangle arrays of a lattice TIN (tin_arrays.hpp).
#include "erase/tin_arrays.hpp"

#include <limits>

namespace tinlod::erase {

bool TinArrays::star(std::int32_t v, int max_ring, std::vector<std::int32_t> &ring,
                     std::vector<std::int32_t> &triangles, std::vector<int> &edge) const {
    ring.clear();
    triangles.clear();
    edge.clear();
    const std::int32_t first = fan[std::size_t(v)];
    if (first < 0)
        return false;
    std::int32_t t = first;
    do {
        const int k = index_of(t, v);
        ring.push_back(at(t, (k + 1) % 3));
        triangles.push_back(t);
        edge.push_back((k + 1) % 3);
        t = across[3 * std::size_t(t) + std::size_t((k + 2) % 3)];
        if (t < 0 || int(ring.size()) > max_ring)
            return false;
    } while (t != first);
    return true;
}

TinArrays tin_arrays(const Mesh &mesh, const Heightfield &hf) {
    TinArrays tin;
    const auto origin = find_origin_property(mesh);
    const std::size_t nodes = mesh.n_vertices();
    tin.sample.resize(nodes);
    tin.col.resize(nodes);
    tin.row.resize(nodes);
    tin.z.resize(nodes);
    tin.outline.assign(nodes, 0);
    tin.fan.assign(nodes, -1);
    for (const auto v : mesh.vertices()) {
        const std::size_t i = std::size_t(v.idx());
        tin.sample[i] = std::uint32_t(mesh.property(origin, v));
        tin.col[i] = std::int32_t(tin.sample[i] % std::uint32_t(hf.width));
        tin.row[i] = std::int32_t(tin.sample[i] / std::uint32_t(hf.width));
        tin.z[i] = double(mesh.point(v)[2]);
    }
    tin.corner.resize(3 * mesh.n_faces());
    tin.across.resize(3 * mesh.n_faces());
    for (const auto f : mesh.faces()) {
        Mesh::HalfedgeHandle h = mesh.halfedge_handle(f);
        for (int k = 0; k < 3; ++k, h = mesh.next_halfedge_handle(h)) {
            const std::size_t i = std::size_t(3 * f.idx() + k);
            tin.corner[i] = mesh.from_vertex_handle(h).idx();
            const Mesh::FaceHandle o = mesh.opposite_face_handle(h);
            tin.across[i] = o.is_valid() ? o.idx() : -1;
            tin.fan[std::size_t(tin.corner[i])] = f.idx();
            if (!o.is_valid()) {
                tin.outline[std::size_t(mesh.from_vertex_handle(h).idx())] = 1;
                tin.outline[std::size_t(mesh.to_vertex_handle(h).idx())] = 1;
            }
        }
    }
    return tin;
}

Mesh nodes_left(const TinArrays &tin, const Mesh &source) {
    Mesh left;
    const auto origin = get_origin_property(left);
    const std::size_t nodes = tin.sample.size();
    // One resize, then the points written in place (add_vertex grows every vertex property per
    // vertex, as in grid_vertices).
    std::vector<std::uint32_t> vertex(nodes);
    std::size_t kept = 0;
    for (std::size_t v = 0; v < nodes; ++v)
        if (tin.fan[v] >= 0)
            vertex[v] = std::uint32_t(kept++);
    left.resize(kept, 0, 0);
    for (std::size_t v = 0; v < nodes; ++v)
        if (tin.fan[v] >= 0) {
            const Mesh::VertexHandle h{int(vertex[v])};
            Mesh::Point p = source.point(Mesh::VertexHandle(int(v)));
            p[2] = float(tin.z[v]);
            left.set_point(h, p);
            left.property(origin, h) = tin.sample[v];
        }
    // The live triangles in slot order; side 3t' + k's twin is the side of triangle `across` that
    // runs back along it (add_triangles' mesh without its search for twins).
    const std::size_t slots = tin.corner.size() / 3;
    std::vector<std::uint32_t> triangle(slots);
    std::size_t live = 0;
    for (std::size_t t = 0; t < slots; ++t)
        if (tin.corner[3 * t] >= 0)
            triangle[t] = std::uint32_t(live++);
    std::vector<std::uint32_t> corners, twins;
    corners.reserve(3 * live);
    twins.reserve(3 * live);
    for (std::size_t t = 0; t < slots; ++t) {
        if (tin.corner[3 * t] < 0)
            continue;
        for (int k = 0; k < 3; ++k) {
            const std::size_t i = 3 * t + std::size_t(k);
            corners.push_back(vertex[std::size_t(tin.corner[i])]);
            const std::int32_t u = tin.across[i];
            twins.push_back(
                u < 0 ? std::numeric_limits<std::uint32_t>::max()
                      : 3 * triangle[std::size_t(u)] +
                            std::uint32_t(tin.index_of(u, tin.at(std::int32_t(t), (k + 1) % 3))));
        }
    }
    add_paired_triangles(left, corners, twins);
    return left;
}

} // namespace tinlod::erase
