// A retrieval's or an insertion's TIN as an OpenMesh mesh (quadtree.hpp, greedy.hpp): on the
// grid frame, or on the whole lattice with vertices for its samples only.
#include "tinlod/greedy.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/tin.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace tinlod {

Mesh to_mesh(const Retrieval &retrieval, const GridFrame &frame) {
    Mesh mesh;
    mesh.reserve(retrieval.nodes.size(), 3 * retrieval.nodes.size(),
                 retrieval.triangles.size() / 3);
    auto origin = get_origin_property(mesh);
    std::vector<std::pair<std::uint32_t, int>> index(retrieval.nodes.size());
    const auto w = static_cast<std::uint32_t>(frame.width);
    for (std::size_t n = 0; n < retrieval.nodes.size(); ++n) {
        const std::uint32_t id = retrieval.nodes[n];
        const auto v = mesh.add_vertex(
            Mesh::Point(float((id % w) * frame.dx), float((id / w) * frame.dy), retrieval.z[n]));
        mesh.property(origin, v) = id;
        index[n] = {id, v.idx()};
    }
    std::sort(index.begin(), index.end());
    auto handle = [&](std::uint32_t id) {
        const auto it = std::lower_bound(index.begin(), index.end(), std::make_pair(id, -1));
        assert(it != index.end() && it->first == id);
        return Mesh::VertexHandle(it->second);
    };
    std::vector<std::uint32_t> corners(retrieval.triangles.size());
    for (std::size_t n = 0; n < corners.size(); ++n)
        corners[n] = std::uint32_t(handle(retrieval.triangles[n]).idx());
    add_triangles(mesh, corners);
    return mesh;
}

// Adds the triangles t (3 vertex indices each, over `vertices` vertices) in the order of their
// first vertex, so the half-edges of nearby nodes lie near each other in memory for an erase that
// sweeps the nodes row by row: a stable counting sort on the first vertex (ties keep the
// retrieval's order; docs/decisions/022-row-order-triangles.md). With `twin` (per side of t, the
// side running the other way, -1 on the outline) the edges are paired by it, not searched for.
static void add_in_row_order(Mesh &mesh, const std::vector<std::uint32_t> &t, std::size_t vertices,
                             const std::vector<std::int32_t> *twin = nullptr) {
    const std::size_t faces = t.size() / 3;
    const auto first = [&](std::size_t k) {
        return std::min({t[3 * k], t[3 * k + 1], t[3 * k + 2]});
    };
    std::vector<std::uint32_t> start(vertices + 1, 0);
    for (std::size_t k = 0; k < faces; ++k)
        ++start[first(k) + 1];
    for (std::size_t v = 0; v + 1 < start.size(); ++v)
        start[v + 1] += start[v];
    std::vector<std::uint32_t> corners(t.size()), at(faces);
    for (std::size_t k = 0; k < faces; ++k) {
        at[k] = start[first(k)]++;
        std::copy_n(t.begin() + std::ptrdiff_t(3 * k), 3,
                    corners.begin() + std::ptrdiff_t(3 * std::size_t(at[k])));
    }
    if (!twin) {
        add_triangles(mesh, corners);
        return;
    }
    std::vector<std::uint32_t> twins(t.size());
    for (std::size_t k = 0; k < faces; ++k)
        for (std::size_t j = 0; j < 3; ++j) {
            const std::int32_t o = (*twin)[3 * k + j];
            twins[3 * std::size_t(at[k]) + j] =
                o < 0 ? std::numeric_limits<std::uint32_t>::max()
                      : 3 * at[std::size_t(o) / 3] + std::uint32_t(o) % 3;
        }
    add_paired_triangles(mesh, corners, twins);
}

Mesh to_lattice_mesh(const Retrieval &retrieval, const Heightfield &hf) {
    Mesh mesh = grid_vertices(hf);
    std::vector<std::uint8_t> held(mesh.n_vertices(), 0);
    for (const std::uint32_t id : retrieval.nodes)
        held[id] = 1;
    for (auto v : mesh.vertices())
        if (!held[v.idx()])
            mesh.status(v).set_deleted(true);
    add_in_row_order(mesh, retrieval.triangles, mesh.n_vertices());
    return mesh;
}

// to_sparse_lattice_mesh, the edges paired by `twin` when given (add_in_row_order).
static Mesh sparse_lattice_mesh(const Retrieval &retrieval, const Heightfield &hf,
                                const std::vector<std::int32_t> *twin) {
    std::vector<std::uint32_t> nodes = retrieval.nodes;
    std::sort(nodes.begin(), nodes.end());
    Mesh mesh;
    mesh.reserve(nodes.size(), 3 * nodes.size(), retrieval.triangles.size() / 3);
    auto origin = get_origin_property(mesh);
    mesh.resize(nodes.size(), 0, 0);
    for (std::size_t k = 0; k < nodes.size(); ++k) {
        const auto w = std::uint32_t(hf.width);
        const int c = int(nodes[k] % w), r = int(nodes[k] / w);
        const Mesh::VertexHandle v{int(k)};
        mesh.set_point(v, grid_point(hf, c, r));
        mesh.property(origin, v) = nodes[k];
    }
    // Vertices in sample order: the triangles' order by first vertex is to_lattice_mesh's. Each
    // corner's vertex from a table by sample where that costs at most 256 bytes a node (a mesh
    // vertex and its edges take more): a search of the sorted nodes per corner took a tenth of a
    // fine simplify's first stage, and half of the conversion after a coarse one's. Else by a
    // search.
    std::vector<std::uint32_t> t(retrieval.triangles.size());
    if (std::size_t(hf.size()) <= 64 * nodes.size()) {
        std::vector<std::uint32_t> vertex(std::size_t(hf.size()));
        for (std::size_t k = 0; k < nodes.size(); ++k)
            vertex[nodes[k]] = std::uint32_t(k);
        for (std::size_t i = 0; i < t.size(); ++i)
            t[i] = vertex[retrieval.triangles[i]];
    } else {
        for (std::size_t i = 0; i < t.size(); ++i)
            t[i] =
                std::uint32_t(std::lower_bound(nodes.begin(), nodes.end(), retrieval.triangles[i]) -
                              nodes.begin());
    }
    add_in_row_order(mesh, t, nodes.size(), twin);
    return mesh;
}

Mesh to_sparse_lattice_mesh(const Retrieval &retrieval, const Heightfield &hf) {
    return sparse_lattice_mesh(retrieval, hf, nullptr);
}

Mesh to_sparse_lattice_mesh(const GreedyTin &greedy, const Heightfield &hf) {
    return sparse_lattice_mesh(greedy.tin, hf, &greedy.twin);
}

} // namespace tinlod
