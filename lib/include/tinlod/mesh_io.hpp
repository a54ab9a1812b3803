// Meshes in and out through OpenMesh IO (PLY, OBJ, OFF, STL by extension), written atomically.
#pragma once

#include "tinlod/tin.hpp"

#include <string>

namespace tinlod {

struct MeshReport {
    std::int64_t vertices = 0;
    std::int64_t faces = 0;
    std::int64_t duplicated_vertices = 0; // added by OpenMesh to split non-manifold edges apart
    std::int64_t isolated_vertices = 0;   // vertices no face uses
    std::int64_t boundary_edges = 0;
    std::int64_t non_manifold_edges = 0; // edges of the file shared by more than two faces
};

// Reads a triangle mesh; the origin property is set to the vertex index in the file. Throws Error
// naming the file when it cannot be read or has no faces. `report` (optional) receives counts.
Mesh read_mesh(const std::string &path, MeshReport *report = nullptr);

// Writes by extension (.ply binary, .obj, .off, .stl binary) through a temporary + rename; throws
// Error naming the file when the folder is missing or unwritable or the extension unknown.
void write_mesh(const Mesh &mesh, const std::string &path);

// True when the extension is a mesh format (as opposed to a raster or store).
bool is_mesh_path(const std::string &path);

} // namespace tinlod
