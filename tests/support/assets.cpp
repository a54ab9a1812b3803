#include "assets.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace tinlod::test {

namespace fs = std::filesystem;

std::string asset(const std::string &name) { return std::string(TINLOD_MESHES_DIR) + "/" + name; }

Heightfield crop(const Heightfield &hf, int x0, int y0, int w, int h) {
    Heightfield c = hf;
    c.width = w;
    c.height = h;
    c.z.resize(std::size_t(w) * h);
    for (int r = 0; r < h; ++r)
        for (int col = 0; col < w; ++col)
            c.at(col, r) = hf.at(x0 + col, y0 + r);
    c.void_mask.clear();
    return c;
}

Heightfield CropCase::load() const {
    return crop(load_heightfield(asset(file)), x0, y0, side, side);
}

std::string CropCase::name() const { return std::string(file) + " at " + std::to_string(bound); }

namespace {
struct TempDirs {
    std::vector<fs::path> dirs;
    ~TempDirs() {
        std::error_code ec;
        for (auto &d : dirs)
            fs::remove_all(d, ec);
    }
};
TempDirs &temp_dirs() {
    static TempDirs t;
    return t;
}
} // namespace

std::string temp_dir() {
    std::random_device rd;
    fs::path p = fs::temp_directory_path() / ("tinlod-test-" + std::to_string(rd()));
    fs::create_directories(p);
    temp_dirs().dirs.push_back(p);
    return p.string();
}

static std::string slurp(const fs::path &p) {
    std::string s;
    if (FILE *f = std::fopen(p.c_str(), "rb")) {
        std::array<char, 4096> buf;
        std::size_t n;
        while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0)
            s.append(buf.data(), n);
        std::fclose(f);
    }
    return s;
}

std::string file_bytes(const std::string &path) { return slurp(path); }

std::map<std::string, std::string> files_under(const std::string &dir) {
    std::map<std::string, std::string> files;
    for (const auto &f : fs::recursive_directory_iterator(dir))
        if (f.is_regular_file())
            files[fs::relative(f.path(), dir).string()] = slurp(f.path().string());
    return files;
}

std::string geotiff_bytes(const std::vector<std::pair<unsigned, std::vector<double>>> &georef,
                          const std::vector<unsigned> &keys, const std::string &nodata) {
    std::string b = "II*";
    b += '\0';
    const auto u16 = [&](unsigned v) { b += char(v & 255), b += char(v >> 8); };
    const auto u32 = [&](unsigned v) { u16(v & 0xffff), u16(v >> 16); };
    // The directory's entries (tag, type, count, value or offset), the data after it: the
    // georeferencing doubles, the GeoKeys, then the samples.
    std::vector<std::array<unsigned, 4>> entries = {
        {256, 3, 1, 2}, {257, 3, 1, 2}, {258, 3, 1, 16}, {259, 3, 1, 1}, {262, 3, 1, 1},
        {273, 4, 1, 0}, {277, 3, 1, 1}, {278, 3, 1, 2},  {279, 4, 1, 8}, {339, 3, 1, 2}};
    const unsigned count = unsigned(entries.size() + georef.size() + 1 + !nodata.empty());
    unsigned at = 8 + 2 + 12 * count + 4;
    for (const auto &[tag, values] : georef) {
        entries.push_back({tag, 12, unsigned(values.size()), at});
        at += unsigned(8 * values.size());
    }
    entries.push_back({34735, 3, unsigned(keys.size()), at});
    at += unsigned(2 * keys.size());
    // GDAL_NODATA's text with its NUL: in the entry itself when it fits in 4 bytes, else after.
    const bool inline_nodata = nodata.size() < 4;
    if (!nodata.empty()) {
        unsigned packed = 0;
        for (std::size_t i = 0; i < nodata.size() && inline_nodata; ++i)
            packed |= unsigned(static_cast<unsigned char>(nodata[i])) << (8 * i);
        entries.push_back({42113, 2, unsigned(nodata.size() + 1), inline_nodata ? packed : at});
        at += inline_nodata ? 0 : unsigned(nodata.size() + 1);
    }
    entries[5][3] = at; // the strip
    u32(8);
    u16(count);
    for (const auto &e : entries) {
        u16(e[0]), u16(e[1]), u32(e[2]);
        e[1] == 3 && e[2] == 1 ? (u16(e[3]), u16(0)) : u32(e[3]);
    }
    u32(0);
    for (const auto &tag : georef)
        for (const double v : tag.second) {
            char raw[8];
            std::memcpy(raw, &v, 8);
            b.append(raw, 8);
        }
    for (const unsigned k : keys)
        u16(k);
    if (!nodata.empty() && !inline_nodata)
        b += nodata + '\0';
    for (const unsigned z : {100u, 200u, 300u, 400u})
        u16(z);
    return b;
}

std::string tiled_tiff_bytes(unsigned w, unsigned h, unsigned tile_w, unsigned tile_h) {
    std::string b = "II*";
    b += '\0';
    const auto u16 = [&](unsigned v) { b += char(v & 255), b += char(v >> 8); };
    const auto u32 = [&](unsigned v) { u16(v & 0xffff), u16(v >> 16); };
    const std::vector<std::array<unsigned, 3>> entries = {
        {256, 4, w},      {257, 4, h},      {258, 3, 16}, {259, 3, 1}, {262, 3, 1}, {277, 3, 1},
        {322, 4, tile_w}, {323, 4, tile_h}, {324, 4, 0},  {325, 4, 8}, {339, 3, 2}};
    const unsigned data = 8 + 2 + 12 * unsigned(entries.size()) + 4;
    u32(8);
    u16(unsigned(entries.size()));
    for (const auto &[tag, type, value] : entries) {
        u16(tag), u16(type), u32(1);
        type == 3 ? (u16(value), u16(0)) : u32(tag == 324 ? data : value);
    }
    u32(0);
    b += std::string(8, '\0');
    return b;
}

std::string png_bytes(int w, int h, int color_type, int bit_depth,
                      const std::vector<unsigned> &samples,
                      const std::vector<std::pair<std::string, std::string>> &chunks) {
    const auto be32 = [](std::uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16 & 255), char(v >> 8 & 255), char(v & 255)};
    };
    const auto crc32 = [](const std::string &bytes) {
        std::uint32_t c = 0xffffffffu;
        for (const unsigned char b : bytes) {
            c ^= b;
            for (int k = 0; k < 8; ++k)
                c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
        }
        return ~c;
    };
    std::string png = "\x89PNG\r\n\x1a\n";
    const auto chunk = [&](const std::string &type, const std::string &data) {
        png += be32(std::uint32_t(data.size())) + type + data + be32(crc32(type + data));
    };
    chunk("IHDR", be32(std::uint32_t(w)) + be32(std::uint32_t(h)) +
                      std::string{char(bit_depth), char(color_type), 0, 0, 0});
    for (const auto &[type, data] : chunks)
        chunk(type, data);
    // Scanlines, each after its filter byte 0 (none), samples big-endian.
    std::string raw;
    if (!samples.empty()) {
        const int channels = color_type == 2 ? 3 : color_type == 4 ? 2 : color_type == 6 ? 4 : 1;
        const std::size_t per_row = std::size_t(w) * channels;
        for (std::size_t i = 0; i < samples.size(); ++i) {
            if (i % per_row == 0)
                raw += '\0';
            if (bit_depth == 16)
                raw += char(samples[i] >> 8);
            raw += char(samples[i] & 255);
        }
    } else {
        raw = std::string(16, '\0');
    }
    // zlib stream of stored blocks, then the Adler-32 of the raw bytes.
    std::string z = "\x78\x01";
    std::uint32_t a = 1, b = 0;
    for (const unsigned char c : raw)
        a = (a + c) % 65521, b = (b + a) % 65521;
    for (std::size_t at = 0; at < raw.size() || at == 0; at += 65535) {
        const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
        z += char(at + n >= raw.size() ? 1 : 0);
        z += {char(n & 255), char(n >> 8), char(~n & 255), char(~n >> 8 & 255)};
        z += raw.substr(at, n);
        if (raw.empty())
            break;
    }
    if (!samples.empty())
        z += be32((b << 16) | a);
    chunk("IDAT", z);
    if (!samples.empty())
        chunk("IEND", "");
    return png;
}

RunResult run_cli(const std::string &args, std::uint64_t max_file_bytes) {
    const fs::path dir = temp_dir();
    // A hang is a failure, not a stuck test run: give up after two minutes (exit status 124),
    // fifteen under the sanitizers, which run the CLI about ten times slower.
#ifdef TINLOD_SANITIZED
    const char *limit = "900";
#else
    const char *limit = "120";
#endif
    const std::string cmd = std::string("timeout ") + limit + " '" + TINLOD_CLI + "' " + args +
                            " >'" + (dir / "out").string() + "' 2>'" + (dir / "err").string() + "'";
    // The limit passes to the child; tinlod ignores SIGXFSZ itself, so that a write past the
    // limit fails with EFBIG instead of killing it.
    rlimit unlimited{};
    getrlimit(RLIMIT_FSIZE, &unlimited);
    if (max_file_bytes > 0) {
        rlimit limited = unlimited;
        limited.rlim_cur = rlim_t(max_file_bytes);
        setrlimit(RLIMIT_FSIZE, &limited);
    }
    const int raw = std::system(cmd.c_str());
    if (max_file_bytes > 0)
        setrlimit(RLIMIT_FSIZE, &unlimited);
    RunResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(dir / "out");
    r.err = slurp(dir / "err");
    return r;
}

pid_t start_cli(const std::vector<std::string> &args, const std::string &err_file) {
    std::vector<char *> argv{const_cast<char *>(TINLOD_CLI)};
    for (const std::string &a : args)
        argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        std::freopen("/dev/null", "w", stdout);
        std::freopen(err_file.empty() ? "/dev/null" : err_file.c_str(), "w", stderr);
        for (const int signal : {SIGINT, SIGTERM, SIGHUP})
            std::signal(signal, SIG_DFL);
        execv(TINLOD_CLI, argv.data());
        _exit(127);
    }
    return pid;
}

// Twice the signed xy area of face f (positive: counter-clockwise seen from above).
static double xy_area2(const Mesh &mesh, Mesh::FaceHandle f) {
    const auto p = face_corners(mesh, f);
    return (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
}

std::int64_t count_folded_faces(const Mesh &mesh) {
    std::int64_t folded = 0;
    for (auto f : mesh.faces())
        folded += xy_area2(mesh, f) <= 0.0;
    return folded;
}

double xy_area(const Mesh &mesh) {
    double sum = 0;
    for (auto f : mesh.faces())
        sum += 0.5 * xy_area2(mesh, f);
    return sum;
}

bool is_sky(const Image &image, std::size_t pixel, const RenderOptions &options) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(image.rgba[4 * pixel + std::size_t(c)]) -
                     int(std::lround(options.sky[c] * 255.0f))) > 1)
            return false;
    return true;
}

} // namespace tinlod::test
