// The library's TIN type and the full-resolution grid TIN.
#include "tinlod/tin.hpp"
#include "tinlod/error.hpp"

#include <algorithm>
#include <cassert>
#include <unordered_map>

namespace tinlod {

OpenMesh::VPropHandleT<std::int64_t> get_origin_property(Mesh& mesh) {
    OpenMesh::VPropHandleT<std::int64_t> handle;
    if (!mesh.get_property_handle(handle, k_origin_property)) {
        mesh.add_property(handle, k_origin_property);
        for (auto v : mesh.vertices())
            mesh.property(handle, v) = v.idx();
    }
    return handle;
}

OpenMesh::VPropHandleT<std::int64_t> find_origin_property(const Mesh& mesh) {
    OpenMesh::VPropHandleT<std::int64_t> handle;
    mesh.get_property_handle(handle, k_origin_property);
    return handle;
}

Mesh grid_vertices(const Heightfield& hf) {
    assert(hf.width >= 2 && hf.height >= 2);
    Mesh mesh;
    const std::size_t n = static_cast<std::size_t>(hf.size());
    mesh.reserve(n, 3 * n, 2 * n);
    auto origin = get_origin_property(mesh);
    for (int r = 0; r < hf.height; ++r)
        for (int c = 0; c < hf.width; ++c) {
            auto v = mesh.add_vertex(Mesh::Point(float(c * hf.dx), float(r * hf.dy), hf.at(c, r)));
            mesh.property(origin, v) = static_cast<std::int64_t>(r) * hf.width + c;
        }
    return mesh;
}

Mesh grid_tin(const Heightfield& hf) {
    Mesh mesh = grid_vertices(hf);
    const int w = hf.width;
    for (int r = 0; r + 1 < hf.height; ++r)
        for (int c = 0; c + 1 < w; ++c) {
            const Mesh::VertexHandle a(r * w + c), b(r * w + c + 1), d(r * w + w + c),
                e(r * w + w + c + 1);
            // Alternate the diagonal so the grid has no preferred direction.
            if ((r + c) % 2 == 0) {
                mesh.add_face(a, b, e);
                mesh.add_face(a, e, d);
            } else {
                mesh.add_face(a, b, d);
                mesh.add_face(b, e, d);
            }
        }
    return mesh;
}

std::array<glm::dvec3, 3> face_corners(const Mesh& mesh, Mesh::FaceHandle f) {
    std::array<glm::dvec3, 3> p;
    int i = 0;
    for (auto v : mesh.fv_range(f)) {
        const auto& q = mesh.point(v);
        p[i++] = glm::dvec3(q[0], q[1], q[2]);
    }
    return p;
}

std::optional<double> grid_surface_height(const Heightfield& hf, double x, double y) {
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

void check_eye_above(const Heightfield& hf, const glm::dvec3& eye, const std::string& subject) {
    const auto ground = grid_surface_height(hf, eye.x, eye.y);
    if (ground && eye.z <= *ground)
        throw Error(subject, "the eye (" + std::to_string(eye.x) + ", " + std::to_string(eye.y) +
                                 ", " + std::to_string(eye.z) + ") is inside the terrain (ground at " +
                                 std::to_string(*ground) + ")");
}

Mesh tin_from_indices(const Heightfield& hf, const std::vector<std::uint32_t>& triangles) {
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
            it->second = mesh.add_vertex(Mesh::Point(float(c * hf.dx), float(r * hf.dy), hf.at(c, r)));
            mesh.property(origin, it->second) = id;
        }
        return it->second;
    };
    for (std::size_t i = 0; i < triangles.size(); i += 3)
        mesh.add_face(vertex(triangles[i]), vertex(triangles[i + 1]), vertex(triangles[i + 2]));
    return mesh;
}

} // namespace tinlod
