// Mesh files through OpenMesh IO, with a report of what the file held and what was dropped.
#include "tinlod/mesh_io.hpp"
#include "tinlod/error.hpp"
#include "tinlod/util.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Utils/Property.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

namespace tinlod {

namespace fs = std::filesystem;

static std::string extension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

bool is_mesh_path(const std::string& path) {
    const std::string ext = extension(path);
    return ext == ".ply" || ext == ".obj" || ext == ".off" || ext == ".stl";
}

// OpenMesh prints "complex edge" and similar complaints on its error stream; we report counts
// instead, so silence it while reading.
struct QuietOpenMesh {
    QuietOpenMesh() { omerr().disable(); omlog().disable(); }
    ~QuietOpenMesh() { omerr().enable(); omlog().enable(); }
};

// OpenMesh splits faces that would make an edge non-manifold onto duplicated vertices. Welding
// vertices by exact position recovers the file's topology, so edges used by more than two faces
// there can be counted.
static std::int64_t count_non_manifold_edges(const Mesh& mesh, std::int64_t& duplicated) {
    std::map<std::array<float, 3>, int> first;
    std::vector<int> weld(mesh.n_vertices());
    for (auto v : mesh.vertices()) {
        const auto& p = mesh.point(v);
        weld[v.idx()] = first.try_emplace({p[0], p[1], p[2]}, v.idx()).first->second;
    }
    duplicated = static_cast<std::int64_t>(mesh.n_vertices() - first.size());
    std::map<std::pair<int, int>, int> uses;
    for (auto f : mesh.faces()) {
        int ids[3], i = 0;
        for (auto v : f.vertices())
            ids[i++] = weld[v.idx()];
        for (int j = 0; j < 3; ++j) {
            const int a = ids[j], b = ids[(j + 1) % 3];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    }
    std::int64_t count = 0;
    for (const auto& [edge, n] : uses)
        count += n > 2;
    return count;
}

Mesh read_mesh(const std::string& path, MeshReport* report) {
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw Error(path, "no such file");
    if (!fs::is_regular_file(path, ec))
        throw Error(path, "not a regular file");
    if (fs::file_size(path, ec) == 0)
        throw Error(path, "file is empty");
    if (!is_mesh_path(path))
        throw Error(path, "unknown mesh format (expected .ply, .obj, .off or .stl)");
    {
        std::ifstream probe(path);
        if (!probe)
            throw Error(path, "cannot open for reading");
    }
    Mesh mesh;
    OpenMesh::IO::Options options;
    bool ok = false;
    try {
        QuietOpenMesh quiet;
        ok = OpenMesh::IO::read_mesh(mesh, path, options);
    } catch (const std::exception& e) {
        throw Error(path, std::string("cannot parse mesh: ") + e.what());
    }
    if (!ok)
        throw Error(path, "cannot parse mesh (truncated or not a valid " + extension(path).substr(1) + " file)");
    if (mesh.n_faces() == 0)
        throw Error(path, "mesh has no faces");
    for (auto v : mesh.vertices()) {
        const auto& p = mesh.point(v);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            throw Error(path, "vertex " + std::to_string(v.idx()) + " has a non-finite coordinate");
    }
    get_origin_property(mesh);
    if (report) {
        *report = MeshReport{};
        report->vertices = static_cast<std::int64_t>(mesh.n_vertices());
        report->faces = static_cast<std::int64_t>(mesh.n_faces());
        report->non_manifold_edges = count_non_manifold_edges(mesh, report->duplicated_vertices);
        for (auto v : mesh.vertices())
            if (mesh.is_isolated(v))
                ++report->isolated_vertices;
        for (auto e : mesh.edges())
            if (mesh.is_boundary(e))
                ++report->boundary_edges;
    }
    return mesh;
}

void write_mesh(const Mesh& input, const std::string& path) {
    const std::string ext = extension(path);
    if (!is_mesh_path(path))
        throw Error(path, "unknown mesh format '" + ext + "' (use .ply, .obj, .off or .stl)");
    const Mesh* mesh = &input;
    Mesh compact;
    const bool garbage =
        std::any_of(input.vertices_sbegin(), input.vertices_end(),
                    [&](auto v) { return input.status(v).deleted(); }) ||
        std::any_of(input.faces_sbegin(), input.faces_end(),
                    [&](auto f) { return input.status(f).deleted(); });
    if (garbage) {
        compact = input;
        compact.garbage_collection();
        mesh = &compact;
    }
    OpenMesh::IO::Options options;
    if (ext == ".ply" || ext == ".stl")
        options += OpenMesh::IO::Options::Binary;
    write_atomically(path, [&](const std::string& tmp) {
        bool ok = false;
        {
            QuietOpenMesh quiet;
            // 9 significant digits keep every float exactly in the ASCII formats.
            ok = OpenMesh::IO::write_mesh(*mesh, tmp, options, 9);
        }
        if (!ok)
            throw Error(path, "cannot write mesh");
    });
}

} // namespace tinlod
