// The focal observation point (paper step 1): where the observation axis (eye -> at) first meets
// the surface, found with a uniform xy grid of faces walked along the ray (2-D DDA), so a query
// costs the cells the ray crosses, not the whole mesh.
//
// When the axis misses the surface (it looks past the terrain, or above the horizon) the focal
// point falls back to the axis' intersection with the horizontal plane z = mean node height, if
// that lies ahead of the eye, and to `view.at` itself otherwise.
#pragma once

#include "tinlod/tin.hpp"
#include "tinlod/view.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace tinlod {

struct FocalPoint {
    glm::dvec3 point{0.0}; // world units
    double distance = 0.0; // |point - eye|, world units
    bool hit = false;      // true when the axis meets the surface; false: fallback (see above)
};

// Spatial index over the live faces of a mesh (a copy of their corners; the mesh may change
// afterwards without invalidating the index, but queries then see the old surface).
class FocalIndex {
  public:
    explicit FocalIndex(const Mesh &mesh);
    // First intersection of the ray from view.eye along view.axis() with the indexed surface.
    FocalPoint cast(const View &view) const;

  private:
    std::vector<glm::vec3> corners_; // 3 per face
    std::vector<std::uint32_t>
        cell_start_; // CSR: faces of cell i are cell_faces_[start[i], start[i+1])
    std::vector<std::uint32_t> cell_faces_;
    glm::dvec2 lo_{0.0}, hi_{0.0};
    double cell_ = 1.0;
    int nx_ = 0, ny_ = 0;
    double mean_z_ = 0.0;
};

// One-off: builds the index and casts once.
FocalPoint focal_point(const Mesh &mesh, const View &view);

} // namespace tinlod
