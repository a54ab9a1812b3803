// The TIN type of the whole library: one OpenMesh triangle mesh with status attributes, and the
// conversion of a Heightfield into its full-resolution grid TIN (the reference for every error).
#pragma once

#include "tinlod/raster.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace tinlod {

struct TinTraits : public OpenMesh::DefaultTraits {
    // local world frame (see Heightfield), so floats keep mm precision
    using Point = OpenMesh::Vec3f;
    using Normal = OpenMesh::Vec3f;
    VertexAttributes(OpenMesh::Attributes::Status);
    FaceAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
    HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<TinTraits>;

// Provenance of each node: the grid sample id (r * width + c) or input vertex index it came from.
// Stored as the mesh vertex property named k_origin_property; get_origin_property adds it when
// the mesh has none.
inline constexpr const char *k_origin_property = "tinlod:origin";
OpenMesh::VPropHandleT<std::int64_t> get_origin_property(Mesh &mesh);
// Returns an invalid handle when the mesh has no provenance.
OpenMesh::VPropHandleT<std::int64_t> find_origin_property(const Mesh &mesh);

// Adds the triangles `corners` (3 vertex indices each) to a mesh that has its vertices and no edge
// yet, building the half-edge arrays in one pass instead of add_face per triangle (which searches
// each corner's fan and reallocates as it goes: about 10x slower for a grid TIN). The result is
// the mesh add_face would give, up to the order of edges and each vertex's first outgoing
// half-edge (a boundary one on the boundary, as OpenMesh requires). Throws std::invalid_argument,
// leaving the mesh as it was, unless the triangles are consistently oriented and form a manifold:
// a corner out of range, a repeated corner, a directed edge used twice or a vertex joining two
// fans.
void add_triangles(Mesh &mesh, std::span<const std::uint32_t> corners);
// add_triangles with each side's twin given (twins[i]: the side running the other way, or
// UINT32_MAX on the boundary), as a mesh's own half-edges or the greedy insertion's give them: the
// same mesh, without the search for twins and its fan test, for triangles known to form an
// oriented manifold (a vertex joining two boundary fans is still refused).
void add_paired_triangles(Mesh &mesh, std::span<const std::uint32_t> corners,
                          std::span<const std::uint32_t> twins);

// The mesh's vertices and faces that are not marked deleted, as a compact mesh of their own, in
// the input's order (garbage_collection instead fills the holes from the arrays' ends); the
// origin property is kept, or set to the input's vertex index when the input has none. For a
// mesh whose live part is small (an erased TIN), faster than garbage_collection through Debian's
// assertion-enabled OpenMesh (docs/decisions/021-live-copy.md).
Mesh live_copy(const Mesh &mesh);

// Sample (c, r)'s node point in grid_tin(hf): the local frame, in the mesh's floats. Every TIN
// over a heightfield's samples places them here, and a lattice's scans rely on it.
inline Mesh::Point grid_point(const Heightfield &hf, int c, int r) {
    return {float(c * hf.dx), float(r * hf.dy), hf.at(c, r)};
}

// Full-resolution grid TIN: W*H nodes, 2(W-1)(H-1) triangles, every triangle counter-clockwise
// seen from above, node i = grid sample i (origin property set).
Mesh grid_tin(const Heightfield &hf);
// grid_tin's nodes alone, with no triangle yet.
Mesh grid_vertices(const Heightfield &hf);

// Height of grid_tin(hf)'s surface at local (x, y) (its triangles, diagonals included), or
// nothing outside the terrain. For "is this eye under the ground?" checks.
std::optional<double> grid_surface_height(const Heightfield &hf, double x, double y);

// Throws Error(subject, ...) when `eye` stands under grid_tin(hf)'s surface.
void check_eye_above(const Heightfield &hf, const glm::dvec3 &eye, const std::string &subject);

// The three corners of face f, in the face's order (counter-clockwise for a TIN seen from above).
std::array<glm::dvec3, 3> face_corners(const Mesh &mesh, Mesh::FaceHandle f);

// Triangles from a compact index list (3 node ids per triangle) over the heightfield samples;
// only the referenced samples become nodes (origin property = sample id). A list that is not an
// oriented manifold (add_triangles) is added face by face, less the faces OpenMesh refuses.
Mesh tin_from_indices(const Heightfield &hf, const std::vector<std::uint32_t> &triangles);

} // namespace tinlod
