// Mesh files that are wrong are refused, naming the line, face or vertex (issue #45 item 5):
// truncated or non-finite STL, out-of-range PLY/OFF/OBJ face indices, non-finite OBJ vertices.
#include "assets.hpp"

#include "tinlod/error.hpp"
#include "tinlod/mesh_io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace tinlod;
using tinlod::test::asset;

namespace {

std::string write(const std::string &name, const std::string &bytes) {
    static const std::string dir = tinlod::test::temp_dir();
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// The reason read_mesh refuses `path` with, or "" when it reads the file.
std::string refusal(const std::string &path) {
    try {
        read_mesh(path);
    } catch (const Error &e) {
        EXPECT_EQ(e.subject(), path);
        return e.reason();
    }
    return "";
}

// The bunny as an ASCII STL, one facet per face, and where each facet starts in the text.
struct AsciiStl {
    std::string text;
    std::vector<std::size_t> facet_starts;
    std::size_t faces = 0;
};

AsciiStl bunny_ascii_stl() {
    const Mesh mesh = read_mesh(asset("bun_zipper_res4.ply"));
    AsciiStl stl;
    std::ostringstream out;
    out.precision(9);
    out << "solid bunny\n";
    for (auto f : mesh.faces()) {
        stl.facet_starts.push_back(std::size_t(out.tellp()));
        out << "  facet normal 0 0 1\n    outer loop\n";
        for (auto v : f.vertices()) {
            const auto &p = mesh.point(v);
            out << "      vertex " << p[0] << " " << p[1] << " " << p[2] << "\n";
        }
        out << "    endloop\n  endfacet\n";
    }
    out << "endsolid bunny\n";
    stl.text = out.str();
    stl.faces = mesh.n_faces();
    return stl;
}

std::string le32(std::uint32_t v) {
    std::string s(4, '\0');
    for (int k = 0; k < 4; ++k)
        s[k] = char(v >> (8 * k));
    return s;
}

std::string le_float(float f) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, 4);
    return le32(bits);
}

// A binary STL of `triangles` (each nine coordinates) under an 80-byte `header`.
std::string binary_stl(const std::string &header,
                       const std::vector<std::vector<float>> &triangles) {
    std::string s = header;
    s.resize(80, ' ');
    s += le32(std::uint32_t(triangles.size()));
    for (const auto &t : triangles) {
        s += le_float(0) + le_float(0) + le_float(1);
        for (float c : t)
            s += le_float(c);
        s += std::string(2, '\0');
    }
    return s;
}

const std::string k_four_vertices_ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float "
                                        "x\nproperty float y\nproperty float z\n";
const std::string k_four_vertices = "0 0 0\n1 0 0\n0 1 0\n1 1 0\n";

} // namespace

TEST(MeshInput, AsciiStlReadsEveryFacet) {
    // The check accepts a well-formed file: every facet becomes a face.
    const AsciiStl stl = bunny_ascii_stl();
    const Mesh mesh = read_mesh(write("bunny.stl", stl.text));
    EXPECT_EQ(mesh.n_faces(), stl.faces);
}

TEST(MeshInput, TruncatedAsciiStlIsRefused) {
    const AsciiStl stl = bunny_ascii_stl();
    const std::size_t half = stl.facet_starts.size() / 2;
    // Cut inside facet `half`: before its second vertex.
    const std::size_t inside =
        stl.text.find("vertex", stl.text.find("vertex", stl.facet_starts[half]) + 1);
    const std::string reason = refusal(write("cut.stl", stl.text.substr(0, inside)));
    EXPECT_NE(reason.find("ends inside facet " + std::to_string(half)), std::string::npos)
        << reason;
    // Cut between two facets: every facet whole, but no endsolid.
    const std::string between =
        refusal(write("between.stl", stl.text.substr(0, stl.facet_starts[half])));
    EXPECT_NE(between.find("no 'endsolid' after " + std::to_string(half) + " facets"),
              std::string::npos)
        << between;
}

TEST(MeshInput, AsciiStlNonFiniteVertexIsRefused) {
    const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex ";
    for (const std::string coords : {"nan inf 5", "0 1 inf", "-inf 1 0", "0 1e39 0", "0 1"}) {
        SCOPED_TRACE(coords);
        // Facet 1's last vertex, on line 13.
        const std::string text = "solid t\n" + facet + "0 1 0\nendloop\nendfacet\n" + facet +
                                 coords + "\nendloop\nendfacet\nendsolid t\n";
        const std::string reason = refusal(write("nan.stl", text));
        EXPECT_NE(reason.find("line 13: facet 1, vertex 2"), std::string::npos) << reason;
        EXPECT_NE(reason.find("not three finite numbers"), std::string::npos) << reason;
    }
}

TEST(MeshInput, BinaryStlNonFiniteVertexIsRefused) {
    const std::vector<float> good = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::vector<float> bad = {1, 1, 0, 2, 1, 0, 1, 2, 0};
    bad[4] = std::numeric_limits<float>::quiet_NaN();
    const std::string reason =
        refusal(write("nan_binary.stl", binary_stl("binary", {good, bad, good})));
    EXPECT_NE(reason.find("facet 1, vertex 1"), std::string::npos) << reason;
    bad[4] = std::numeric_limits<float>::infinity();
    EXPECT_NE(refusal(write("inf_binary.stl", binary_stl("binary", {bad}))).find("facet 0"),
              std::string::npos);
}

TEST(MeshInput, BinaryStlWhoseHeaderSaysSolidReadsAsBinary) {
    // Some exporters start the binary header with "solid": the size decides, as in OpenMesh.
    const std::vector<float> a = {0, 0, 0, 1, 0, 0, 0, 1, 0}, b = {1, 0, 0, 1, 1, 0, 0, 1, 0};
    const Mesh mesh = read_mesh(write("solid_binary.stl", binary_stl("solid exported", {a, b})));
    EXPECT_EQ(mesh.n_faces(), 2u);
}

TEST(MeshInput, AsciiPlyIndexOutOfRangeIsRefused) {
    for (const std::string index : {"100000", "-1", "4"}) {
        SCOPED_TRACE(index);
        // Face 1 is the bad one; face 0 alone would read.
        const std::string two = k_four_vertices_ply +
                                "element face 2\nproperty list uchar int vertex_indices\n"
                                "end_header\n" +
                                k_four_vertices + "3 0 1 2\n3 1 " + index + " 2\n";
        const std::string reason = refusal(write("index.ply", two));
        EXPECT_NE(reason.find("PLY face 1: vertex index " + index + " is out of range"),
                  std::string::npos)
            << reason;
        // Alone, it is still named (not "mesh has no faces").
        const std::string one = k_four_vertices_ply +
                                "element face 1\nproperty list uchar int vertex_indices\n"
                                "end_header\n" +
                                k_four_vertices + "3 1 " + index + " 2\n";
        const std::string alone = refusal(write("alone.ply", one));
        EXPECT_NE(alone.find("PLY face 0: vertex index " + index), std::string::npos) << alone;
    }
}

TEST(MeshInput, BinaryPlyIndexOutOfRangeIsRefused) {
    for (const bool big : {false, true}) {
        for (const std::int32_t index : {100000, -1}) {
            SCOPED_TRACE(std::to_string(big) + " " + std::to_string(index));
            auto i32 = [&](std::uint32_t v) {
                std::string s = le32(v);
                return big ? std::string(s.rbegin(), s.rend()) : s;
            };
            auto f32 = [&](float f) {
                std::uint32_t bits = 0;
                std::memcpy(&bits, &f, 4);
                return i32(bits);
            };
            std::string ply = std::string("ply\nformat ") +
                              (big ? "binary_big_endian" : "binary_little_endian") +
                              " 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 2\n"
                              "property list uchar int vertex_indices\nend_header\n";
            for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f})
                ply += f32(v);
            for (const std::vector<std::uint32_t> &face :
                 {std::vector<std::uint32_t>{0, 1, 2}, {1, std::uint32_t(index), 2}}) {
                ply.push_back('\3');
                for (const std::uint32_t corner : face)
                    ply += i32(corner);
            }
            const std::string reason = refusal(write("index_binary.ply", ply));
            EXPECT_NE(reason.find("PLY face 1: vertex index " + std::to_string(index) +
                                  " is out of range (the file has 4 vertices)"),
                      std::string::npos)
                << reason;
        }
    }
}

TEST(MeshInput, OffIndexOutOfRangeIsRefused) {
    const std::string ascii = "OFF\n4 2 0\n" + k_four_vertices + "3 0 1 2\n3 1 100000 2\n";
    const std::string reason = refusal(write("index.off", ascii));
    EXPECT_NE(reason.find("OFF face 1: vertex index 100000 is out of range"), std::string::npos)
        << reason;
    std::string binary = "OFF BINARY\n" + le32(4) + le32(2) + le32(0);
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f})
        binary += le_float(v);
    binary += le32(3) + le32(0) + le32(1) + le32(2) + le32(3) + le32(1) + le32(7) + le32(2);
    const std::string binary_reason = refusal(write("index_binary.off", binary));
    EXPECT_NE(binary_reason.find("OFF face 1: vertex index 7 is out of range"), std::string::npos)
        << binary_reason;
}

TEST(MeshInput, ObjNonFiniteVertexOrBadIndexIsRefused) {
    const std::string nan = refusal(write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"));
    EXPECT_NE(nan.find("OBJ line 2: vertex 1 is not three finite numbers"), std::string::npos)
        << nan;
    const std::string far =
        refusal(write("far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 100000\n"));
    EXPECT_NE(far.find("OBJ line 5: vertex index 100000 is out of range"), std::string::npos)
        << far;
    const std::string back = refusal(write("back.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n"));
    EXPECT_NE(back.find("OBJ line 3: face 0: vertex index -3"), std::string::npos) << back;
    // Relative indices that stay in range read.
    EXPECT_EQ(read_mesh(write("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n")).n_faces(),
              1u);
}

TEST(MeshInput, CliNamesTheFileAndLeavesNoOutput) {
    const std::string bad = write("cli_nan.stl", "solid t\nfacet normal 0 0 1\nouter loop\n"
                                                 "vertex 0 0 0\nvertex nan inf 5\n");
    const std::string dir = tinlod::test::temp_dir();
    const auto r = tinlod::test::run_cli("simplify '" + bad + "' --eye 0,0,10 --at 0,0,0 -o '" +
                                         dir + "/out.ply'");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err.rfind("tinlod: error: " + bad + ": ASCII STL line 5", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
    EXPECT_FALSE(std::ifstream(dir + "/out.ply").good());
}
