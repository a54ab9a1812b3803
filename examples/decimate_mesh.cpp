// Your own OpenMesh mesh, decimated for a viewer at a distance so that no vertex of it moves more
// than a tolerance in screen pixels: with tinlod's module in OpenMesh's stock DecimaterT, or with
// tinlod's node erase in the same conventions. Only OpenMesh and the tinlod/om headers.
//   decimate_mesh IN OUT.ply decay|erase DISTANCE [TOLERANCE_PX]
// The eye stands DISTANCE from the mesh's box centre, above it (direction (0.2, 0.3, 1)).
#include "tinlod/om/ModDistanceDecayT.hh"
#include "tinlod/om/NodeEraseDecimaterT.hh"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

int main(int argc, char **argv) {
    if (argc != 5 && argc != 6) {
        std::fprintf(stderr,
                     "usage: decimate_mesh IN OUT.ply decay|erase DISTANCE [TOLERANCE_PX]\n");
        return 2;
    }
    const std::string module = argv[3];
    const double tolerance = argc == 6 ? std::atof(argv[5]) : 1.0;
    Mesh mesh;
    if ((module != "decay" && module != "erase") || !OpenMesh::IO::read_mesh(mesh, argv[1])) {
        std::fprintf(stderr, "decimate_mesh: error: %s: cannot read, or unknown module\n", argv[1]);
        return 1;
    }
    const std::size_t input_vertices = mesh.n_vertices();

    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (auto v : mesh.vertices()) {
        const auto &p = mesh.point(v);
        lo = glm::min(lo, glm::dvec3(p[0], p[1], p[2]));
        hi = glm::max(hi, glm::dvec3(p[0], p[1], p[2]));
    }
    tinlod::View view; // 1920 x 1080 pixels, 60 degrees of vertical field of view
    view.at = 0.5 * (lo + hi);
    view.eye = view.at + std::atof(argv[4]) * glm::normalize(glm::dvec3(0.2, 0.3, 1.0));

    // Status attributes outlive the decimater, for garbage_collection() afterwards.
    mesh.request_vertex_status();
    mesh.request_edge_status();
    mesh.request_face_status();
    if (module == "decay") {
        OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
        tinlod::om::ModDistanceDecayT<Mesh>::Handle decay;
        decimater.add(decay);
        decimater.module(decay).set_view(view); // before initialize()
        decimater.module(decay).set_tolerance(tolerance);
        if (!decimater.initialize())
            return std::fprintf(stderr, "decimate_mesh: error: cannot initialize\n"), 1;
        decimater.decimate();
    } else {
        tinlod::om::NodeEraseDecimaterT<Mesh> decimater(mesh);
        decimater.set_view(view);
        decimater.set_tolerance(tolerance);
        if (!decimater.initialize())
            return std::fprintf(stderr, "decimate_mesh: error: not a triangle mesh\n"), 1;
        decimater.decimate();
    }
    mesh.garbage_collection();

    if (!OpenMesh::IO::write_mesh(mesh, argv[2], OpenMesh::IO::Options::Binary)) {
        std::fprintf(stderr, "decimate_mesh: error: %s: cannot write\n", argv[2]);
        return 1;
    }
    std::printf("vertices %zu -> %zu eye %.17g %.17g %.17g at %.17g %.17g %.17g\n", input_vertices,
                mesh.n_vertices(), view.eye.x, view.eye.y, view.eye.z, view.at.x, view.at.y,
                view.at.z);
    return 0;
}
