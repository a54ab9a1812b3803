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
#include <iostream>
#include <sstream>
#include <map>
#include <set>

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

// OpenMesh prints "complex edge" and similar complaints on its streams and on std::cerr; we
// report counts instead, so silence them while reading.
struct QuietOpenMesh {
    QuietOpenMesh() : cerr_(std::cerr.rdbuf(nullptr)) { omerr().disable(); omlog().disable(); }
    ~QuietOpenMesh() {
        omerr().enable();
        omlog().enable();
        std::cerr.rdbuf(cerr_);
    }
    std::streambuf* cerr_;
};

// OpenMesh's readers loop forever on a PLY header without end_header and allocate whatever
// count a header declares. Check the header and the declared counts against the file size first.
static void check_header(const std::string& path, const std::string& ext, std::uintmax_t bytes) {
    std::ifstream in(path, std::ios::binary);
    std::string head(std::size_t(std::min<std::uintmax_t>(bytes, 1 << 16)), '\0');
    in.read(head.data(), std::streamsize(head.size()));
    auto too_many = [&](const char* what, std::uintmax_t count, std::uintmax_t min_bytes) {
        if (count > bytes / min_bytes)
            throw Error(path, "header declares " + std::to_string(count) + " " + what +
                                  " but the file holds only " + std::to_string(bytes) + " bytes");
    };
    if (ext == ".ply") {
        if (head.rfind("ply", 0) != 0)
            throw Error(path, "not a PLY file (no 'ply' magic)");
        const auto end = head.find("end_header");
        if (end == std::string::npos)
            throw Error(path, "truncated or malformed PLY header (no end_header)");
        // OpenMesh's PLY reader also loops forever on a malformed format line: accept only the
        // header grammar of the PLY specification.
        static const std::set<std::string> k_types = {
            "char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
            "int16", "uint16", "int32", "uint32", "float32", "float64"};
        std::istringstream lines(head.substr(0, end));
        std::string line;
        int number = 0;
        while (std::getline(lines, line)) {
            ++number;
            if (!line.empty() && line.back() == '\r')
                line.pop_back();
            std::istringstream words(line);
            std::string key, a, b, c, extra;
            words >> key;
            const std::string where = "PLY header line " + std::to_string(number) + ": ";
            if (number == 1 ? key != "ply" : key.empty())
                throw Error(path, where + "malformed '" + line + "'");
            if (key == "ply" || key == "comment" || key == "obj_info")
                continue;
            if (key == "format") {
                if (!(words >> a >> b) || (words >> extra) || b != "1.0" ||
                    (a != "ascii" && a != "binary_little_endian" && a != "binary_big_endian"))
                    throw Error(path, where + "unknown format '" + line + "'");
            } else if (key == "element") {
                std::uintmax_t count = 0;
                if (!(words >> a >> count) || (words >> extra))
                    throw Error(path, where + "malformed element '" + line + "'");
                too_many(a == "face" ? "faces" : "elements", count, 1);
            } else if (key == "property") {
                words >> a;
                const bool ok = a == "list" ? (words >> b >> c) && k_types.count(b) && k_types.count(c)
                                            : k_types.count(a) > 0;
                if (!ok || !(words >> extra) || (words >> extra))
                    throw Error(path, where + "malformed property '" + line + "'");
            } else {
                throw Error(path, where + "unknown keyword '" + key + "'");
            }
        }
    } else if (ext == ".off") {
        std::istringstream words(head);
        std::string magic;
        std::uintmax_t nv = 0, nf = 0;
        words >> magic;
        if (magic.find("OFF") == std::string::npos)
            throw Error(path, "not an OFF file (no 'OFF' magic)");
        if (magic.find("BINARY") == std::string::npos && (words >> nv >> nf)) {
            too_many("vertices", nv, 6);
            too_many("faces", nf, 6);
        }
    } else if (ext == ".stl" && head.rfind("solid", 0) != 0 && bytes >= 84) {
        const auto* p = reinterpret_cast<const unsigned char*>(head.data()) + 80;
        const std::uintmax_t n = p[0] | p[1] << 8 | p[2] << 16 | std::uintmax_t(p[3]) << 24;
        if (84 + 50 * n != bytes)
            throw Error(path, "binary STL declares " + std::to_string(n) + " triangles but holds " +
                                  std::to_string(bytes) + " bytes");
    }
}

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
    check_header(path, extension(path), fs::file_size(path, ec));
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
