// The library's TIN type and the full-resolution grid TIN.
#include "tinlod/tin.hpp"
#include "tinlod/error.hpp"

#include <algorithm>
#include <cassert>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace tinlod {

OpenMesh::VPropHandleT<std::int64_t> get_origin_property(Mesh &mesh) {
    OpenMesh::VPropHandleT<std::int64_t> handle;
    if (!mesh.get_property_handle(handle, k_origin_property)) {
        mesh.add_property(handle, k_origin_property);
        for (auto v : mesh.vertices())
            mesh.property(handle, v) = v.idx();
    }
    return handle;
}

OpenMesh::VPropHandleT<std::int64_t> find_origin_property(const Mesh &mesh) {
    OpenMesh::VPropHandleT<std::int64_t> handle;
    mesh.get_property_handle(handle, k_origin_property);
    return handle;
}

namespace {

constexpr std::uint32_t k_none = std::numeric_limits<std::uint32_t>::max();

// The mesh of the triangles `corners` over its vertices, with side i's half-edge half[i] (edge
// half[i] / 2), `open` the sides without a twin, whose boundary half-edges are half[i] ^ 1.
void build_paired(Mesh &mesh, std::span<const std::uint32_t> corners,
                  const std::vector<std::uint32_t> &half, const std::vector<std::uint32_t> &open,
                  std::uint32_t edges) {
    using HH = Mesh::HalfedgeHandle;
    const std::size_t faces = corners.size() / 3;
    const auto to = [&](std::size_t i) { return corners[i % 3 == 2 ? i - 2 : i + 1]; };
    mesh.resize(mesh.n_vertices(), edges, faces);
    for (std::size_t f = 0; f < faces; ++f) {
        const Mesh::FaceHandle fh{int(f)};
        for (int k = 0; k < 3; ++k) {
            const std::size_t i = 3 * f + std::size_t(k);
            const HH h{int(half[i])};
            mesh.set_vertex_handle(h, Mesh::VertexHandle(int(corners[k == 2 ? i - 2 : i + 1])));
            mesh.set_face_handle(h, fh);
            mesh.set_next_halfedge_handle(h, HH(int(half[k == 2 ? i - 2 : i + 1])));
            mesh.set_halfedge_handle(Mesh::VertexHandle(int(corners[i])), h);
        }
        mesh.set_halfedge_handle(fh, HH(int(half[3 * f + 2]))); // as add_face: the last side
    }
    // Boundary half-edges (no face) leave the ends of the sides without a twin; each boundary
    // vertex keeps its one boundary half-edge as its outgoing one and links the next to it.
    for (const std::uint32_t i : open) {
        const HH h(int(half[i] ^ 1u));
        mesh.set_vertex_handle(h, Mesh::VertexHandle(int(corners[i])));
        mesh.set_halfedge_handle(Mesh::VertexHandle(int(to(i))), h);
    }
    for (const std::uint32_t i : open) {
        const HH h(int(half[i] ^ 1u));
        mesh.set_next_halfedge_handle(h, mesh.halfedge_handle(Mesh::VertexHandle(int(corners[i]))));
    }
}

// Side i's half-edge: edge e holds 2e (the first side met) and 2e + 1 (its twin, or the boundary
// half-edge running the other way when it has none), given each side's twin (k_none: none).
std::uint32_t number_edges(std::span<const std::uint32_t> twin_of, std::vector<std::uint32_t> &half,
                           std::vector<std::uint32_t> &open) {
    half.assign(twin_of.size(), k_none);
    std::uint32_t edges = 0;
    for (std::size_t i = 0; i < twin_of.size(); ++i) {
        if (half[i] != k_none)
            continue;
        half[i] = 2 * edges;
        if (twin_of[i] != k_none)
            half[twin_of[i]] = 2 * edges + 1;
        else
            open.push_back(std::uint32_t(i));
        ++edges;
    }
    return edges;
}

// Each boundary vertex must have one boundary half-edge leaving it (checked before the mesh
// changes, so a refused list leaves it as it was).
void check_boundary(std::span<const std::uint32_t> corners, const std::vector<std::uint32_t> &open,
                    std::size_t n) {
    std::vector<std::uint8_t> boundary_out(n, 0);
    for (const std::uint32_t i : open)
        if (boundary_out[corners[i % 3 == 2 ? i - 2 : i + 1]]++)
            throw std::invalid_argument("add_triangles: a vertex joins two boundary fans");
}

} // namespace

void add_triangles(Mesh &mesh, std::span<const std::uint32_t> corners) {
    if (corners.size() % 3 != 0 || mesh.n_edges() != 0 || mesh.n_faces() != 0)
        throw std::invalid_argument("add_triangles: a mesh with faces, or a partial triangle");
    const std::size_t n = mesh.n_vertices(), sides = corners.size();
    if (sides >= std::size_t(std::numeric_limits<std::int32_t>::max()) / 2)
        throw std::invalid_argument("add_triangles: too many triangles");
    // Side i of face i / 3 runs from corners[i] to the next corner of its face; the loops over the
    // sides go face by face, where that corner needs no division.
    const auto for_each_side = [&](auto &&visit) {
        for (std::size_t f = 0; f < sides; f += 3) {
            visit(f, corners[f], corners[f + 1]);
            visit(f + 1, corners[f + 1], corners[f + 2]);
            visit(f + 2, corners[f + 2], corners[f]);
        }
    };
    // The sides leaving each vertex (counting sort by origin), to find each side's twin.
    std::vector<std::uint32_t> first(n + 1, 0);
    for_each_side([&](std::size_t, std::uint32_t a, std::uint32_t b) {
        if (a >= n || a == b)
            throw std::invalid_argument("add_triangles: a corner out of range or repeated");
        ++first[a + 1];
    });
    for (std::size_t v = 0; v < n; ++v)
        first[v + 1] += first[v];
    std::vector<std::uint32_t> leaving(sides), ends(sides), fill(first.begin(), first.end() - 1);
    for_each_side([&](std::size_t i, std::uint32_t a, std::uint32_t b) {
        const std::uint32_t k = fill[a]++;
        leaving[k] = std::uint32_t(i);
        ends[k] = b;
    });
    // Each side's half-edge: edge e holds 2e (the first side met) and 2e + 1 (its twin, or the
    // boundary half-edge running the other way when it has none). A directed edge used twice
    // shows as a side with two twins, or as a twin met again after it was paired (or, with no side
    // the other way, as two boundary half-edges leaving one vertex, refused below).
    std::vector<std::uint32_t> half(sides, k_none), twin_of(sides, k_none);
    std::vector<std::uint32_t> open; // sides without a twin, by edge
    std::uint32_t edges = 0;
    for_each_side([&](std::size_t i, std::uint32_t a, std::uint32_t b) {
        if (half[i] != k_none)
            return;
        half[i] = 2 * edges;
        std::uint32_t twin = k_none;
        for (std::uint32_t k = first[b]; k < first[b + 1]; ++k)
            if (ends[k] == a) {
                if (twin != k_none)
                    throw std::invalid_argument("add_triangles: a directed edge used twice");
                twin = leaving[k];
            }
        if (twin != k_none) {
            if (twin_of[twin] != k_none)
                throw std::invalid_argument("add_triangles: a directed edge used twice");
            half[twin] = 2 * edges + 1;
            twin_of[i] = twin;
            twin_of[twin] = std::uint32_t(i);
        } else {
            open.push_back(std::uint32_t(i));
        }
        ++edges;
    });
    check_boundary(corners, open, n);
    // And each vertex one fan: turning from side to side around it (the twin of the side before in
    // the same face) from its open side, or from any side, meets every side leaving it.
    std::vector<std::uint32_t> start(n, k_none);
    for (const std::uint32_t i : open)
        start[corners[i]] = i;
    for (std::size_t v = 0; v < n; ++v) {
        const std::uint32_t degree = first[v + 1] - first[v];
        if (degree == 0)
            continue;
        const std::uint32_t from = start[v] != k_none ? start[v] : leaving[first[v]];
        std::uint32_t met = 0;
        for (std::uint32_t i = from; i != k_none && met <= degree;) {
            ++met;
            i = twin_of[i % 3 == 0 ? i + 2 : i - 1];
            if (i == from)
                break;
        }
        if (met != degree)
            throw std::invalid_argument("add_triangles: a vertex joins two fans");
    }
    build_paired(mesh, corners, half, open, edges);
}

void add_paired_triangles(Mesh &mesh, std::span<const std::uint32_t> corners,
                          std::span<const std::uint32_t> twins) {
    if (corners.size() % 3 != 0 || twins.size() != corners.size() || mesh.n_edges() != 0 ||
        mesh.n_faces() != 0)
        throw std::invalid_argument(
            "add_paired_triangles: a mesh with faces, a partial triangle or a twin list's size");
    std::vector<std::uint32_t> half, open;
    const std::uint32_t edges = number_edges(twins, half, open);
    check_boundary(corners, open, mesh.n_vertices());
    build_paired(mesh, corners, half, open, edges);
}

Mesh grid_vertices(const Heightfield &hf) {
    assert(hf.width >= 2 && hf.height >= 2);
    Mesh mesh;
    const std::size_t n = static_cast<std::size_t>(hf.size());
    mesh.reserve(n, 3 * n, 2 * n);
    auto origin = get_origin_property(mesh);
    // One resize, then the points written in place: add_vertex grows every vertex property per
    // sample (docs/decisions/003-grid-vertices.md).
    mesh.resize(n, 0, 0);
    for (int r = 0; r < hf.height; ++r)
        for (int c = 0; c < hf.width; ++c) {
            const std::int64_t id = static_cast<std::int64_t>(r) * hf.width + c;
            const Mesh::VertexHandle v{int(id)};
            mesh.set_point(v, grid_point(hf, c, r));
            mesh.property(origin, v) = id;
        }
    return mesh;
}

Mesh live_copy(const Mesh &mesh) {
    Mesh out;
    const auto from = find_origin_property(mesh);
    const auto to = get_origin_property(out);
    // One resize, then the points written in place (add_vertex grows every vertex property per
    // vertex, as in grid_vertices).
    std::vector<std::uint32_t> map(mesh.n_vertices());
    std::size_t live = 0;
    for (auto v : mesh.vertices())
        map[v.idx()] = std::uint32_t(live++);
    out.resize(live, 0, 0);
    for (auto v : mesh.vertices()) {
        const Mesh::VertexHandle w{int(map[v.idx()])};
        out.set_point(w, mesh.point(v));
        out.property(to, w) = from.is_valid() ? mesh.property(from, v) : v.idx();
    }
    // The faces' corners in f.vertices()' order, as add_triangles takes them: side 3f + k runs
    // along the face's half-edge k + 1 (from its half-edge's end). Each side's twin is the side
    // of the opposite half-edge, so the mesh is add_triangles' without its search for twins and
    // its fan test (the input is a mesh already; docs/decisions/038-simplify-speed-7-floor.md).
    std::vector<std::uint32_t> corners, side_of(mesh.n_halfedges(), k_none), along;
    corners.reserve(3 * mesh.n_faces());
    along.reserve(3 * mesh.n_faces());
    for (auto f : mesh.faces()) {
        Mesh::HalfedgeHandle h = mesh.halfedge_handle(f);
        for (int k = 0; k < 3; ++k) {
            corners.push_back(map[mesh.to_vertex_handle(h).idx()]);
            h = mesh.next_halfedge_handle(h);
            side_of[std::size_t(h.idx())] = std::uint32_t(corners.size() - 1);
            along.push_back(std::uint32_t(h.idx()));
        }
    }
    std::vector<std::uint32_t> twin_of(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i)
        twin_of[i] = side_of[std::size_t(
            mesh.opposite_halfedge_handle(Mesh::HalfedgeHandle(int(along[i]))).idx())];
    add_paired_triangles(out, corners, twin_of);
    return out;
}

Mesh grid_tin(const Heightfield &hf) {
    Mesh mesh = grid_vertices(hf);
    const std::uint32_t w = std::uint32_t(hf.width);
    std::vector<std::uint32_t> corners;
    corners.reserve(6 * std::size_t(w - 1) * std::size_t(hf.height - 1));
    for (std::uint32_t r = 0; r + 1 < std::uint32_t(hf.height); ++r)
        for (std::uint32_t c = 0; c + 1 < w; ++c) {
            const std::uint32_t a = r * w + c, b = a + 1, d = a + w, e = d + 1;
            // Alternate the diagonal so the grid has no preferred direction.
            if ((r + c) % 2 == 0)
                corners.insert(corners.end(), {a, b, e, a, e, d});
            else
                corners.insert(corners.end(), {a, b, d, b, e, d});
        }
    add_triangles(mesh, corners);
    return mesh;
}

std::array<glm::dvec3, 3> face_corners(const Mesh &mesh, Mesh::FaceHandle f) {
    std::array<glm::dvec3, 3> p;
    int i = 0;
    for (auto v : mesh.fv_range(f)) {
        const auto &q = mesh.point(v);
        p[i++] = glm::dvec3(q[0], q[1], q[2]);
    }
    return p;
}

std::optional<double> grid_surface_height(const Heightfield &hf, double x, double y) {
    const double u = x / hf.dx, v = y / hf.dy;
    if (!(u >= 0 && v >= 0 && u <= hf.width - 1 && v <= hf.height - 1))
        return std::nullopt;
    const int c = std::min(int(u), hf.width - 2), r = std::min(int(v), hf.height - 2);
    const double s = u - c, t = v - r;
    const double a = hf.at(c, r), b = hf.at(c + 1, r), d = hf.at(c, r + 1), e = hf.at(c + 1, r + 1);
    // The same diagonals as grid_tin: a-e on even cells, b-d on odd ones.
    if ((r + c) % 2 == 0)
        return s >= t ? a + s * (b - a) + t * (e - b) : a + t * (d - a) + s * (e - d);
    return s + t <= 1 ? a + s * (b - a) + t * (d - a) : e + (1 - s) * (d - e) + (1 - t) * (b - e);
}

void check_eye_above(const Heightfield &hf, const glm::dvec3 &eye, const std::string &subject) {
    const auto ground = grid_surface_height(hf, eye.x, eye.y);
    if (ground && eye.z <= *ground)
        throw Error(subject, "the eye (" + std::to_string(eye.x) + ", " + std::to_string(eye.y) +
                                 ", " + std::to_string(eye.z) +
                                 ") is inside the terrain (ground at " + std::to_string(*ground) +
                                 ")");
}

Mesh tin_from_indices(const Heightfield &hf, const std::vector<std::uint32_t> &triangles) {
    assert(triangles.size() % 3 == 0);
    Mesh mesh;
    auto origin = get_origin_property(mesh);
    std::unordered_map<std::uint32_t, Mesh::VertexHandle> node;
    node.reserve(triangles.size() / 2);
    auto vertex = [&](std::uint32_t id) {
        auto [it, fresh] = node.try_emplace(id);
        if (fresh) {
            const int c = static_cast<int>(id % static_cast<std::uint32_t>(hf.width));
            const int r = static_cast<int>(id / static_cast<std::uint32_t>(hf.width));
            it->second = mesh.add_vertex(grid_point(hf, c, r));
            mesh.property(origin, it->second) = id;
        }
        return it->second;
    };
    std::vector<std::uint32_t> corners(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i)
        corners[i] = std::uint32_t(vertex(triangles[i]).idx());
    try {
        add_triangles(mesh, corners);
    } catch (const std::invalid_argument &) {
        // Not an oriented manifold (a peer's output may not be): face by face, as OpenMesh takes
        // them.
        for (std::size_t i = 0; i < corners.size(); i += 3)
            mesh.add_face(Mesh::VertexHandle(int(corners[i])),
                          Mesh::VertexHandle(int(corners[i + 1])),
                          Mesh::VertexHandle(int(corners[i + 2])));
    }
    return mesh;
}

} // namespace tinlod
