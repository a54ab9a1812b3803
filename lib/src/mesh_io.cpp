// Mesh files through OpenMesh IO, with a report of what the file held and what was dropped.
#include "tinlod/mesh_io.hpp"
#include "tinlod/error.hpp"
#include "tinlod/util.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Utils/Property.hh>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

namespace tinlod {

namespace fs = std::filesystem;

static std::string extension(const std::string &path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext;
}

bool is_mesh_path(const std::string &path) {
    const std::string ext = extension(path);
    return ext == ".ply" || ext == ".obj" || ext == ".off" || ext == ".stl";
}

// OpenMesh prints "complex edge" and similar complaints on its streams and on std::cerr; we
// report counts instead, so silence them while reading.
struct QuietOpenMesh {
    QuietOpenMesh() : cerr_(std::cerr.rdbuf(nullptr)) {
        omerr().disable();
        omlog().disable();
    }
    ~QuietOpenMesh() {
        omerr().enable();
        omlog().enable();
        std::cerr.rdbuf(cerr_);
    }
    std::streambuf *cerr_;
};

// --- Checks before OpenMesh reads a file ---
//
// OpenMesh 9.0's readers trust their input. They loop forever on a PLY header without end_header
// or with a malformed format line, allocate whatever count a header declares, and take a face's
// vertex count as given: a 94-byte PLY or OFF whose face declares 4000000000 vertices makes them
// allocate 32 GB. Once a value fails to parse, their ASCII readers go on looping over the declared
// counts with the last face's vertex count (never set if the first face fails): hundreds of
// milliseconds of spinning for a mangled bunny, or the 32 GB again. So the header and its counts
// are checked against the file, and the body of a PLY or OFF file is walked here first, value by
// value as OpenMesh will read it: a file is refused unless every value it will read is there and
// parses, after which OpenMesh's loops run on good values only.
//
// They also add a face whose vertex index is out of range as nothing (a PLY or OFF face naming
// vertex 100000 of 100, or -1, vanished, and a file of only such faces read as "no faces"), and
// the STL readers weld vertices through a std::map whose ordering a NaN breaks (undefined
// behaviour: one run put a vertex at y = 1.8e31). So indices are checked against the vertex count
// and STL coordinates for finiteness here, naming the line, face or vertex at fault.

[[noreturn]] static void refuse(const std::string &path, const std::string &why) {
    throw Error(path, why);
}

static void check_count(const std::string &path, const char *what, std::uintmax_t count,
                        std::uintmax_t bytes, std::uintmax_t min_bytes) {
    if (count > bytes / min_bytes)
        refuse(path, "header declares " + std::to_string(count) + " " + what +
                         " but the file holds only " + std::to_string(bytes) + " bytes");
}

// `face` is the face's number in the file, for the message only (built when refusing).
static void check_index(const std::string &path, const char *format, std::uintmax_t face,
                        std::int64_t index, std::uintmax_t vertices) {
    if (index < 0 || std::uintmax_t(index) >= vertices)
        refuse(path, format + (" face " + std::to_string(face)) + ": vertex index " +
                         std::to_string(index) + " is out of range (the file has " +
                         std::to_string(vertices) + " vertices)");
}

// A coordinate as OpenMesh's text readers parse it (into a float): the whole word a number whose
// float is finite. "nan", "inf" and 1e39 are not. The word lies in a NUL-terminated line.
static bool finite_coordinate(std::string_view word) {
    char *end = nullptr;
    const double v = std::strtod(word.data(), &end);
    return !word.empty() && end == word.data() + word.size() &&
           std::isfinite(static_cast<float>(v));
}

// The next blank-separated word of a line from `at` on, or an empty one at its end.
static std::string_view next_word(const std::string &line, std::size_t &at) {
    const std::size_t begin = std::min(line.find_first_not_of(" \t\r\v\f", at), line.size());
    at = std::min(line.find_first_of(" \t\r\v\f", begin), line.size());
    return std::string_view(line).substr(begin, at - begin);
}

// Whether `word` is the lowercase `keyword` in any case.
static bool is_keyword(std::string_view word, std::string_view keyword) {
    return word.size() == keyword.size() &&
           std::equal(word.begin(), word.end(), keyword.begin(),
                      [](char a, char b) { return std::tolower((unsigned char)a) == b; });
}

struct PlyProperty {
    std::string name;
    std::string type;       // the value's type, or the type of a list's entries
    std::string count_type; // a list's count type; empty for a scalar
};

struct PlyElement {
    std::string name;
    std::uintmax_t count = 0;
    std::vector<PlyProperty> properties;
};

struct PlyHeader {
    bool ascii = true;
    bool big_endian = false;
    std::vector<PlyElement> elements;
    std::uintmax_t ascii_body = 0;  // where OpenMesh's ASCII reader goes on: after "end_header"
    std::uintmax_t binary_body = 0; // where its binary reader seeks to, by its own arithmetic
};

// The number of vertices a PLY face may index.
static std::uintmax_t ply_vertices(const PlyHeader &h) {
    for (const PlyElement &e : h.elements)
        if (e.name == "vertex")
            return e.count;
    return 0;
}

// How OpenMesh's PLY reader reads a property (by element and property name, as its header parser).
enum class PlyRead { coordinate, color, indices, other };

static PlyRead ply_read(const PlyElement &e, const PlyProperty &p) {
    static const std::set<std::string> k_coordinates = {"x",  "y", "z", "nx", "ny",
                                                        "nz", "u", "s", "v",  "t"};
    static const std::set<std::string> k_vertex_colors = {
        "red", "green", "blue", "alpha", "diffuse_red", "diffuse_green", "diffuse_blue"};
    static const std::set<std::string> k_face_colors = {"red", "green", "blue", "alpha"};
    if (!p.count_type.empty())
        return e.name == "face" && (p.name == "vertex_index" || p.name == "vertex_indices")
                   ? PlyRead::indices
                   : PlyRead::other;
    if (e.name == "vertex" && k_coordinates.count(p.name))
        return PlyRead::coordinate;
    if ((e.name == "vertex" && k_vertex_colors.count(p.name)) ||
        (e.name == "face" && k_face_colors.count(p.name)))
        return PlyRead::color;
    return PlyRead::other;
}

static std::uintmax_t ply_type_bytes(const std::string &type) {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
        return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
        return 2;
    if (type == "double" || type == "float64")
        return 8;
    return 4;
}

static bool ply_is_float(const std::string &type) { return type == "float" || type == "float32"; }
static bool ply_is_real(const std::string &type) {
    return ply_is_float(type) || type == "double" || type == "float64";
}

// The header as OpenMesh's PLY reader parses it, refused unless it follows the PLY grammar (which
// OpenMesh assumes without checking) and its counts fit in the file.
static PlyHeader parse_ply_header(const std::string &path, const std::string &head,
                                  std::uintmax_t bytes) {
    static const std::set<std::string> k_types = {
        "char", "uchar", "short", "ushort", "int",   "uint",   "float",   "double",
        "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
    static const std::set<std::string> k_keywords = {"ply",     "format",   "element",   "property",
                                                     "comment", "obj_info", "end_header"};
    if (head.rfind("ply", 0) != 0)
        refuse(path, "not a PLY file (no 'ply' magic)");
    PlyHeader h;
    std::uintmax_t token_end = 0; // OpenMesh's stream position before it reads end_header
    int number = 0;
    for (std::size_t start = 0; start < head.size(); ++number) {
        const std::size_t nl = head.find('\n', start);
        if (nl == std::string::npos)
            break;
        std::string line = head.substr(start, nl - start);
        const std::size_t line_start = start;
        start = nl + 1;
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        std::istringstream words(line);
        std::string key, a, b, c, extra;
        words >> key;
        const std::string where = "PLY header line " + std::to_string(number + 1) + ": ";
        if (number == 0 ? key != "ply" : key.empty())
            refuse(path, where + "malformed '" + line + "'");
        if (number == 1 && key != "format")
            refuse(path, where + "expected the format line, found '" + line + "'");
        if (key == "end_header") {
            h.ascii_body = line_start + line.find("end_header") + 10;
            const bool crlf = token_end + 1 < head.size() && head[token_end] == '\r' &&
                              head[token_end + 1] == '\n';
            h.binary_body = token_end + (crlf ? 14 : 12);
            return h;
        }
        // Past the last word of the line, or past the whole line for a comment (OpenMesh reads
        // the rest of a comment line, and word by word otherwise).
        token_end = key == "comment" ? start : line_start + line.find_last_not_of(" \t\v\f") + 1;
        if (key == "ply" || key == "comment")
            continue;
        if (key == "obj_info") {
            // OpenMesh skips its words one by one as unknown keywords: none may be a keyword.
            while (words >> a)
                if (k_keywords.count(a))
                    refuse(path, where + "obj_info holds the keyword '" + a + "'");
        } else if (key == "format") {
            if (number != 1 || !(words >> a >> b) || (words >> extra) || b != "1.0" ||
                (a != "ascii" && a != "binary_little_endian" && a != "binary_big_endian"))
                refuse(path, where + "unknown format '" + line + "'");
            h.ascii = a == "ascii";
            h.big_endian = a == "binary_big_endian";
        } else if (key == "element") {
            PlyElement e;
            if (!(words >> e.name >> e.count) || (words >> extra))
                refuse(path, where + "malformed element '" + line + "'");
            check_count(path, e.name == "face" ? "faces" : "elements", e.count, bytes, 1);
            for (const PlyElement &other : h.elements)
                if (other.name == e.name && (e.name == "vertex" || e.name == "face"))
                    refuse(path, where + "a second '" + e.name + "' element");
            h.elements.push_back(e);
        } else if (key == "property") {
            PlyProperty p;
            words >> a;
            const bool list = a == "list";
            const bool ok = list ? (words >> b >> c) && k_types.count(b) && k_types.count(c)
                                 : k_types.count(a) > 0;
            if (!ok || !(words >> p.name) || (words >> extra))
                refuse(path, where + "malformed property '" + line + "'");
            if (h.elements.empty())
                refuse(path, where + "property before any element");
            p.type = list ? c : a;
            if (list)
                p.count_type = b;
            h.elements.back().properties.push_back(p);
        } else {
            refuse(path, where + "unknown keyword '" + key + "'");
        }
    }
    refuse(path, "truncated or malformed PLY header (no end_header)");
}

// Every value OpenMesh's ASCII reader will extract, with the same types and in the same order.
static void walk_ply_ascii(const std::string &path, const PlyHeader &h) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(std::streamoff(h.ascii_body));
    float real = 0;
    int integer = 0;
    unsigned count = 0;
    std::int64_t index = 0;
    std::string word;
    const std::uintmax_t vertices = ply_vertices(h);
    for (const PlyElement &e : h.elements) {
        if (in.eof())
            return; // OpenMesh stops here: "unexpected end of file"
        for (std::uintmax_t n = 0; n < e.count && !in.eof(); ++n)
            for (const PlyProperty &p : e.properties) {
                switch (ply_read(e, p)) {
                case PlyRead::coordinate:
                    in >> real;
                    break;
                case PlyRead::color:
                    if (ply_is_float(p.type))
                        in >> real;
                    else
                        in >> integer;
                    break;
                case PlyRead::indices:
                    in >> count;
                    for (unsigned k = 0; k < count && in >> index; ++k)
                        check_index(path, "PLY", n, index, vertices);
                    break;
                case PlyRead::other:
                    in >> word;
                    break;
                }
                if (!in)
                    refuse(path, "truncated or malformed PLY body: " + e.name + " " +
                                     std::to_string(n) + ", property '" + p.name + "'");
            }
        if (e.name == "face")
            return; // OpenMesh reads nothing after the faces
    }
}

static bool ply_is_signed(const std::string &type) {
    return type == "char" || type == "int8" || type == "short" || type == "int16" ||
           type == "int" || type == "int32";
}

// A binary PLY integer of `n` bytes (indices are integers: walk_ply_binary refuses real ones).
static std::int64_t ply_integer(const unsigned char *raw, std::uintmax_t n, bool is_signed,
                                bool big_endian) {
    std::uint64_t bits = 0;
    for (std::uintmax_t k = 0; k < n; ++k)
        bits |= std::uint64_t(raw[big_endian ? n - 1 - k : k]) << (8 * k);
    if (is_signed && n < 8 && (bits >> (8 * n - 1)) & 1)
        return std::int64_t(bits) - (std::int64_t{1} << (8 * n));
    return std::int64_t(bits);
}

// The bytes OpenMesh's binary reader will consume, and every face's vertex count.
static void walk_ply_binary(const std::string &path, const PlyHeader &h, std::uintmax_t bytes) {
    const std::uintmax_t vertices = ply_vertices(h);
    std::ifstream in(path, std::ios::binary);
    in.seekg(std::streamoff(std::min(h.binary_body, bytes)));
    std::uintmax_t at = h.binary_body;
    for (const PlyElement &e : h.elements) {
        auto take = [&](std::uintmax_t n) {
            if (at > bytes || n > bytes - at)
                refuse(path, "truncated PLY body: the " + e.name +
                                 " elements need more than the file's " + std::to_string(bytes) +
                                 " bytes");
            at += n;
        };
        // Bytes OpenMesh consumes per property (0 for the vertex list, read below).
        std::vector<std::uintmax_t> width;
        std::uintmax_t fixed = 0;
        bool has_indices = false;
        for (const PlyProperty &p : e.properties) {
            std::uintmax_t w = ply_type_bytes(p.type); // of a list: one entry, all OpenMesh skips
            switch (ply_read(e, p)) {
            case PlyRead::coordinate: // read as float or double, else as nothing
                w = ply_is_real(p.type) ? w : 0;
                break;
            case PlyRead::color: // read as float or as an integer; a double as nothing
                w = ply_is_float(p.type) || !ply_is_real(p.type) ? w : 0;
                break;
            case PlyRead::indices:
                if (ply_is_real(p.type))
                    refuse(path, "PLY vertex indices of type " + p.type +
                                     " (OpenMesh reads integers only)");
                has_indices = true;
                w = 0;
                break;
            case PlyRead::other:
                break;
            }
            width.push_back(w);
            fixed += w;
        }
        if (!has_indices) {
            if (fixed > 0 && e.count > bytes / fixed)
                take(bytes + 1);
            take(e.count * fixed);
            in.ignore(std::streamsize(e.count * fixed));
        } else {
            for (std::uintmax_t n = 0; n < e.count; ++n)
                for (std::size_t i = 0; i < e.properties.size(); ++i) {
                    const PlyProperty &p = e.properties[i];
                    if (ply_read(e, p) != PlyRead::indices) {
                        take(width[i]);
                        in.ignore(std::streamsize(width[i]));
                        continue;
                    }
                    const std::uintmax_t count_bytes = ply_type_bytes(p.count_type);
                    take(count_bytes);
                    unsigned char raw[8] = {};
                    in.read(reinterpret_cast<char *>(raw), std::streamsize(count_bytes));
                    std::uint32_t count = 0;
                    for (std::uintmax_t k = 0; k < count_bytes && k < 4; ++k)
                        count |= std::uint32_t(raw[h.big_endian ? count_bytes - 1 - k : k])
                                 << (8 * k);
                    const std::uintmax_t entry_bytes = ply_type_bytes(p.type);
                    const bool is_signed = ply_is_signed(p.type);
                    take(std::uintmax_t{count} * entry_bytes);
                    for (std::uint32_t k = 0; k < count; ++k) {
                        in.read(reinterpret_cast<char *>(raw), std::streamsize(entry_bytes));
                        check_index(path, "PLY", n,
                                    ply_integer(raw, entry_bytes, is_signed, h.big_endian),
                                    vertices);
                    }
                }
        }
        if (e.name == "face")
            return;
    }
}

// OFF: OpenMesh reads the first line as a header, [ST][C][N][4][n]OFF [BINARY], then the counts.
static void check_off(const std::string &path, const std::string &head, std::uintmax_t bytes) {
    const std::string first = head.substr(0, head.find('\n'));
    std::size_t p = 0;
    const bool texcoords = first.rfind("ST", 0) == 0;
    p += texcoords ? 2 : 0;
    const bool colors = first.size() > p && first[p] == 'C';
    p += colors;
    const bool normals = first.size() > p && first[p] == 'N';
    p += normals;
    if (first.compare(p, 3, "OFF") != 0)
        refuse(path, "not an OFF file (no 'OFF' magic)");
    const bool binary = first.size() >= p + 10 && first.compare(p + 4, 6, "BINARY") == 0;
    std::ifstream in(path, std::ios::binary);
    std::string line;
    std::getline(in, line);
    if (binary) {
        std::uintmax_t at = line.size() + 1;
        unsigned char raw[12] = {};
        if (!in.read(reinterpret_cast<char *>(raw), 12))
            refuse(path, "truncated binary OFF: no counts");
        at += 12;
        auto u32 = [&](const unsigned char *b) {
            return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                   std::uint32_t(b[3]) << 24;
        };
        const std::uintmax_t nv = u32(raw), nf = u32(raw + 4);
        // OpenMesh reads colours as three 32-bit integers in a binary file.
        const std::uintmax_t vertex_bytes = 12 + 12 * normals + 12 * colors + 8 * texcoords;
        check_count(path, "vertices", nv, bytes, vertex_bytes);
        check_count(path, "faces", nf, bytes, 4);
        in.ignore(std::streamsize(nv * vertex_bytes));
        at += nv * vertex_bytes;
        for (std::uintmax_t f = 0; f < nf; ++f) {
            if (at > bytes || bytes - at < 4 || !in.read(reinterpret_cast<char *>(raw), 4))
                refuse(path, "truncated binary OFF: face " + std::to_string(f) + " of " +
                                 std::to_string(nf));
            at += 4;
            const std::uintmax_t count = u32(raw);
            if (count > (bytes - at) / 4)
                refuse(path, "truncated binary OFF: face " + std::to_string(f) + " declares " +
                                 std::to_string(count) + " vertices");
            for (std::uintmax_t k = 0; k < count; ++k) {
                in.read(reinterpret_cast<char *>(raw), 4);
                check_index(path, "OFF", f, u32(raw), nv);
            }
            at += 4 * count;
        }
        return;
    }
    unsigned nv = 0, nf = 0, ne = 0;
    if (!(in >> nv >> nf >> ne))
        refuse(path, "malformed OFF counts (expected vertices, faces and edges on line 2)");
    check_count(path, "vertices", nv, bytes, 6);
    check_count(path, "faces", nf, bytes, 6);
    float real = 0;
    unsigned count = 0;
    std::int64_t index = 0;
    for (unsigned v = 0; v < nv && !in.eof(); ++v) {
        in >> real >> real >> real;
        if (normals)
            in >> real >> real >> real;
        if (!in)
            refuse(path, "truncated or malformed OFF: vertex " + std::to_string(v));
        std::getline(in, line); // colours and texture coordinates, parsed apart from the stream
    }
    for (unsigned f = 0; f < nf; ++f) {
        in >> count;
        for (unsigned k = 0; k < count && in >> index; ++k)
            check_index(path, "OFF", f, index, nv);
        if (!in)
            refuse(path, "truncated or malformed OFF: face " + std::to_string(f));
        if (colors)
            std::getline(in, line);
    }
}

// OBJ: OpenMesh's reader asserts (aborts the process) on a face vertex without a position index
// ("f /2 3"), takes a position that fails to parse as whatever value it read last, and drops a
// face whose index names no vertex. The OBJ grammar asks every face vertex for an integer
// position: v, v/vt, v//vn or v/vt/vn, counted from 1, or back from the last vertex when negative.
static void check_obj(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::string line, word;
    std::int64_t vertices = 0, faces = 0;
    std::int64_t last_index = 0, last_line = 0; // the largest position index, checked at the end
    for (std::int64_t number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        const std::string where = "OBJ line " + std::to_string(number);
        if (!(words >> word))
            continue;
        if (word == "v") {
            std::string x, y, z;
            if (!(words >> x >> y >> z) || !finite_coordinate(x) || !finite_coordinate(y) ||
                !finite_coordinate(z))
                refuse(path, where + ": vertex " + std::to_string(vertices) +
                                 " is not three finite numbers");
            ++vertices;
            continue;
        }
        if (word != "f")
            continue;
        while (words >> word) {
            const std::size_t slash = word.find('/');
            std::istringstream position(word.substr(0, slash));
            int index = 0;
            if (!(position >> index)) {
                if (slash == std::string::npos)
                    continue; // OpenMesh skips a lone word that is not a number
                refuse(path, where + ": face vertex '" + word + "' has no position index");
            }
            if (index < 0 && -std::int64_t{index} > vertices)
                refuse(path, where + ": face " + std::to_string(faces) + ": vertex index " +
                                 std::to_string(index) + " reaches back past the " +
                                 std::to_string(vertices) + " vertices before it");
            if (index == 0)
                refuse(path, where + ": face " + std::to_string(faces) +
                                 ": vertex index 0 (OBJ counts from 1)");
            if (index > last_index) {
                last_index = index;
                last_line = number;
            }
        }
        ++faces;
    }
    if (last_index > vertices)
        refuse(path, "OBJ line " + std::to_string(last_line) + ": vertex index " +
                         std::to_string(last_index) + " is out of range (the file has " +
                         std::to_string(vertices) + " vertices)");
}

// STL: the readers weld vertices through a std::map, which a NaN coordinate corrupts, and the
// ASCII one leaves a coordinate that fails to parse uninitialised and stops without complaint at
// the end of the file, wherever it is. So an ASCII file must follow the grammar to its 'endsolid'
// with finite vertices, and a binary file's vertices must be finite.
static void check_stl_ascii(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    // The keywords of a facet, in order, from "facet" to "endfacet".
    static const std::array<std::string_view, 7> k_facet = {
        "facet", "outer", "vertex", "vertex", "vertex", "endloop", "endfacet"};
    enum class State { solid, facet_or_end, in_facet };
    State state = State::solid;
    std::size_t step = 0;
    std::int64_t facets = 0, number = 0;
    auto where = [&] { return "ASCII STL line " + std::to_string(number) + ": "; };
    while (std::getline(in, line)) {
        ++number;
        std::size_t at = 0;
        const std::string_view word = next_word(line, at);
        if (word.empty())
            continue;
        auto found = [&] { return "found '" + std::string(word.substr(0, 40)) + "'"; };
        if (state == State::solid) {
            if (!is_keyword(word, "solid"))
                refuse(path, where() + "expected 'solid', " + found());
            state = State::facet_or_end;
        } else if (state == State::facet_or_end) {
            if (is_keyword(word, "endsolid")) {
                state = State::solid;
            } else if (is_keyword(word, "facet")) {
                state = State::in_facet;
                step = 1;
            } else {
                refuse(path, where() + "expected 'facet' or 'endsolid', " + found());
            }
        } else {
            if (!is_keyword(word, k_facet[step]))
                refuse(path, where() + "facet " + std::to_string(facets) + ": expected '" +
                                 std::string(k_facet[step]) + "', " + found());
            if (k_facet[step] == "vertex") {
                const std::size_t coordinates = at;
                const std::string_view x = next_word(line, at), y = next_word(line, at),
                                       z = next_word(line, at);
                if (!finite_coordinate(x) || !finite_coordinate(y) || !finite_coordinate(z) ||
                    !next_word(line, at).empty()) {
                    std::string given = line.substr(coordinates);
                    given.erase(0, given.find_first_not_of(" \t"));
                    given.erase(given.find_last_not_of(" \t\r") + 1);
                    refuse(path, where() + "facet " + std::to_string(facets) + ", vertex " +
                                     std::to_string(step - 2) + ": '" + given +
                                     "' is not three finite numbers");
                }
            }
            if (++step == k_facet.size()) {
                state = State::facet_or_end;
                ++facets;
            }
        }
    }
    if (state == State::in_facet)
        refuse(path, "truncated ASCII STL: the file ends inside facet " + std::to_string(facets) +
                         " (line " + std::to_string(number) + ")");
    if (state == State::facet_or_end)
        refuse(path, "truncated ASCII STL: no 'endsolid' after " + std::to_string(facets) +
                         " facets (line " + std::to_string(number) + ")");
}

static void check_stl_binary(const std::string &path, std::uintmax_t triangles) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(84);
    constexpr std::uintmax_t k_batch = 4096; // facets per read
    std::vector<char> buffer(50 * k_batch);
    for (std::uintmax_t first = 0; first < triangles; first += k_batch) {
        const std::uintmax_t n = std::min(k_batch, triangles - first);
        in.read(buffer.data(), std::streamsize(50 * n));
        for (std::uintmax_t t = 0; t < n; ++t)
            for (int k = 0; k < 9; ++k) {
                // After the facet's normal (12 bytes), three corners of three little-endian floats.
                const auto *b =
                    reinterpret_cast<const unsigned char *>(buffer.data()) + 50 * t + 12 + 4 * k;
                const std::uint32_t bits = std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 |
                                           std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
                float v = 0;
                std::memcpy(&v, &bits, 4);
                if (!std::isfinite(v))
                    refuse(path, "binary STL facet " + std::to_string(first + t) + ", vertex " +
                                     std::to_string(k / 3) + ": non-finite coordinate");
            }
    }
}

static void check_header(const std::string &path, const std::string &ext, std::uintmax_t bytes) {
    std::ifstream in(path, std::ios::binary);
    std::string head(std::size_t(std::min<std::uintmax_t>(bytes, 1 << 16)), '\0');
    in.read(head.data(), std::streamsize(head.size()));
    if (ext == ".ply") {
        const PlyHeader h = parse_ply_header(path, head, bytes);
        if (h.ascii)
            walk_ply_ascii(path, h);
        else
            walk_ply_binary(path, h, bytes);
    } else if (ext == ".off") {
        check_off(path, head, bytes);
    } else if (ext == ".obj") {
        check_obj(path);
    } else if (ext == ".stl") {
        // OpenMesh takes a file as binary when its size fits the triangle count it declares, even
        // when its 80-byte header starts with "solid", as some exporters write.
        std::uintmax_t n = 0;
        if (bytes >= 84) {
            const auto *p = reinterpret_cast<const unsigned char *>(head.data()) + 80;
            n = p[0] | p[1] << 8 | p[2] << 16 | std::uintmax_t(p[3]) << 24;
        }
        if (bytes >= 84 && 84 + 50 * n == bytes)
            check_stl_binary(path, n);
        else if (head.rfind("solid", 0) == 0)
            check_stl_ascii(path);
        else if (bytes >= 84)
            refuse(path, "binary STL declares " + std::to_string(n) + " triangles but holds " +
                             std::to_string(bytes) + " bytes");
        else
            refuse(path, "not an STL file (no 'solid', and shorter than a binary header)");
    }
}

// OpenMesh splits faces that would make an edge non-manifold onto duplicated vertices. Welding
// vertices by exact position recovers the file's topology, so edges used by more than two faces
// there can be counted.
static std::int64_t count_non_manifold_edges(const Mesh &mesh, std::int64_t &duplicated) {
    std::map<std::array<float, 3>, int> first;
    std::vector<int> weld(mesh.n_vertices());
    for (auto v : mesh.vertices()) {
        const auto &p = mesh.point(v);
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
    for (const auto &[edge, n] : uses)
        count += n > 2;
    return count;
}

Mesh read_mesh(const std::string &path, MeshReport *report) {
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
    } catch (const std::exception &e) {
        throw Error(path, std::string("cannot parse mesh: ") + e.what());
    }
    if (!ok)
        throw Error(path, "cannot parse mesh (truncated or not a valid " +
                              extension(path).substr(1) + " file)");
    if (mesh.n_faces() == 0)
        throw Error(path, "mesh has no faces");
    for (auto v : mesh.vertices()) {
        const auto &p = mesh.point(v);
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

// Binary STL written here, byte for byte as OpenMesh 9.0's writer: its 80-byte header, the face
// count, then per face the unit normal ((c - b) x (a - b), in float), the corners in the face's
// circulator order and a zero attribute. OpenMesh's goes through a virtual exporter and a stream
// call per float: 2,700 instructions a triangle, where this takes about 100.
static void write_stl_binary(const Mesh &mesh, std::ostream &out) {
    static constexpr char header[80] =
        "binary stl file                                                                ";
    out.write(header, sizeof header);
    const auto put = [](char *&at, const void *value, std::size_t bytes) {
        std::memcpy(at, value, bytes);
        at += bytes;
    };
    static_assert(sizeof(float) == 4 && std::endian::native == std::endian::little);
    const std::uint32_t faces = std::uint32_t(mesh.n_faces());
    out.write(reinterpret_cast<const char *>(&faces), 4);
    constexpr std::size_t k_record = 50, k_chunk = 4096;
    std::vector<char> buffer(k_record * k_chunk);
    char *at = buffer.data();
    for (auto f : mesh.faces()) {
        std::array<OpenMesh::Vec3f, 3> p;
        int i = 0;
        for (auto v : f.vertices())
            p[std::size_t(i++)] = mesh.point(v);
        OpenMesh::Vec3f n = (p[2] - p[1]) % (p[0] - p[1]);
        n.normalize();
        put(at, n.data(), 12);
        for (const auto &q : p)
            put(at, q.data(), 12);
        const std::uint16_t attribute = 0;
        put(at, &attribute, 2);
        if (at == buffer.data() + buffer.size()) {
            out.write(buffer.data(), std::streamsize(buffer.size()));
            at = buffer.data();
        }
    }
    out.write(buffer.data(), at - buffer.data());
}

void write_mesh(const Mesh &input, const std::string &path) {
    const std::string ext = extension(path);
    if (!is_mesh_path(path))
        throw Error(path, "unknown mesh format '" + ext + "' (use .ply, .obj, .off or .stl)");
    // OpenMesh's writers visit deleted elements too (a face's corners then come from freed
    // half-edges): a mesh holding some, as a refiner's TIN between frames, is written as its live
    // part. The plain iterators see every element; the skipping ones (`_sbegin`) would hide them.
    // OpenMesh's compaction, not live_copy: a surface mesh may join two boundary fans at a vertex,
    // which live_copy refuses.
    const Mesh *mesh = &input;
    Mesh compact;
    const bool garbage = std::any_of(input.vertices_begin(), input.vertices_end(),
                                     [&](auto v) { return input.status(v).deleted(); }) ||
                         std::any_of(input.faces_begin(), input.faces_end(),
                                     [&](auto f) { return input.status(f).deleted(); });
    if (garbage) {
        compact = input;
        compact.garbage_collection();
        mesh = &compact;
    }
    OpenMesh::IO::Options options;
    if (ext == ".ply" || ext == ".stl")
        options += OpenMesh::IO::Options::Binary;
    write_atomically(path, [&](const std::string &tmp) {
        // Through a stream of our own: OpenMesh's file writers do not look at their stream's state,
        // so a full disk left a short file and a success.
        std::ofstream out(tmp, std::ios::binary);
        if (!out)
            throw Error(path, "cannot write mesh: " + std::string(std::strerror(errno)));
        // 9 significant digits in the text formats, which keep every float exactly (OpenMesh's
        // stream writers take the stream's precision; its OBJ file writer wrote 9 decimals, in
        // fixed notation, which moved values below 1 by up to 5e-10).
        out.precision(9);
        bool ok = true;
        if (ext == ".stl") {
            write_stl_binary(*mesh, out);
        } else {
            QuietOpenMesh quiet;
            ok = OpenMesh::IO::write_mesh(*mesh, out, ext, options, 9);
        }
        if (!ok)
            throw Error(path, "cannot write mesh");
        if (!out.flush())
            throw Error(path, "cannot write mesh: " + std::string(std::strerror(errno)));
    });
}

} // namespace tinlod
