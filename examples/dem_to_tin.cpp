// A view-independent TIN from a DEM: greedy insertion until every sample is within a vertical
// bound, written as a mesh.
//   dem_to_tin DEM MAX_ERROR OUT.ply      (MAX_ERROR in the DEM's height units, e.g. metres)
#include "tinlod/error.hpp"
#include "tinlod/greedy.hpp"
#include "tinlod/mesh_io.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"

#include <cstdio>
#include <cstdlib>

int main(int argc, char **argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: dem_to_tin DEM MAX_ERROR OUT.ply\n");
        return 2;
    }
    try {
        const tinlod::Heightfield hf = tinlod::load_heightfield(argv[1]);
        tinlod::GreedyOptions options;
        options.max_error = std::atof(argv[2]);
        const tinlod::GreedyTin tin = tinlod::greedy_tin(hf, options);
        // The TIN on the DEM's lattice: the samples it left out are deleted vertices.
        tinlod::Mesh mesh = tinlod::to_lattice_mesh(tin.tin, hf);
        mesh.garbage_collection();
        tinlod::write_mesh(mesh, argv[3]);
        std::printf("samples %lld nodes %zu triangles %zu max_error %g\n",
                    static_cast<long long>(hf.size()), mesh.n_vertices(), mesh.n_faces(),
                    options.max_error);
    } catch (const tinlod::Error &e) {
        std::fprintf(stderr, "dem_to_tin: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
