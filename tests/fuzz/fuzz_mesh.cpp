// Fuzz target: mesh files through our OpenMesh IO wrapper (PLY, OBJ, OFF, STL).
// The first byte picks the format; the rest is the file.
#include "fuzz_input.hpp"

#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    if (size < 1)
        return 0;
    static const char *k_ext[] = {".ply", ".obj", ".off", ".stl"};
    const std::string path = tinlod::fuzz::write_input(data + 1, size - 1, k_ext[data[0] % 4]);
    try {
        tinlod::MeshReport report;
        const tinlod::Mesh mesh = tinlod::read_mesh(path, &report);
        if (mesh.n_faces() == 0)
            __builtin_trap(); // read_mesh promises at least one face
    } catch (const tinlod::Error &) {
    }
    std::remove(path.c_str());
    return 0;
}
