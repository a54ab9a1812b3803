// Pieces the benchmarks share: larger terrains made from real ones (Catmull-Rom enlargement plus
// value-noise detail), crops, the xy fold-over count of a TIN, child processes (run and timed as a
// whole), the npm peers (delatin, martini) on a grid, and result rows as CSV.
//
// Enlargement: bicubic (Catmull-Rom) resampling of a real DEM to (cells*s + 1) samples per side
// over the same ground (cells s times smaller), plus fractal detail at the new scale: 4 octaves of
// value noise, the finest 4 new cells wide with amplitude 0.5 m, each coarser octave twice as wide
// and 1.6x as strong (about 8 m of detail in all, well below the real relief).
#pragma once

#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/util.hpp"

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <sched.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace tinlod::bench {

inline float catmull_rom(float p0, float p1, float p2, float p3, float t) {
    return p1 + 0.5f * t *
                    (p2 - p0 + t * (2 * p0 - 5 * p1 + 4 * p2 - p3 + t * (3 * (p1 - p2) + p3 - p0)));
}

inline float hash01(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
    std::uint32_t h = x * 374761393u + y * 668265263u + seed * 2246822519u;
    h = (h ^ (h >> 13)) * 1274126177u;
    return float((h ^ (h >> 16)) & 0xFFFFFF) / float(0xFFFFFF) - 0.5f;
}

inline float value_noise(double u, double v, std::uint32_t seed) {
    const auto x = std::uint32_t(u), y = std::uint32_t(v);
    const float fx = float(u - x), fy = float(v - y);
    const float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
    const float a = hash01(x, y, seed), b = hash01(x + 1, y, seed), c = hash01(x, y + 1, seed),
                d = hash01(x + 1, y + 1, seed);
    return a + (b - a) * sx + (c - a) * sy + (a - b - c + d) * sx * sy;
}

// `src` enlarged by `scale` (see the file comment): round((width-1)*scale)+1 samples per side.
inline Heightfield enlarge(const Heightfield &src, double scale) {
    Heightfield out;
    const int cells = int(std::lround((src.width - 1) * scale));
    out.width = out.height = cells + 1;
    out.dx = src.dx * (src.width - 1) / cells;
    out.dy = src.dy * (src.height - 1) / cells;
    out.crs = src.crs;
    out.z.resize(std::size_t(out.width) * out.height);
    auto at = [&](int c, int r) {
        return src.at(std::clamp(c, 0, src.width - 1), std::clamp(r, 0, src.height - 1));
    };
    for (int r = 0; r < out.height; ++r) {
        const double v = double(r) * (src.height - 1) / cells;
        const int r0 = std::min(int(v), src.height - 2);
        const float tv = float(v - r0);
        for (int c = 0; c < out.width; ++c) {
            const double u = double(c) * (src.width - 1) / cells;
            const int c0 = std::min(int(u), src.width - 2);
            const float tu = float(u - c0);
            float rows[4];
            for (int k = 0; k < 4; ++k)
                rows[k] = catmull_rom(at(c0 - 1, r0 - 1 + k), at(c0, r0 - 1 + k),
                                      at(c0 + 1, r0 - 1 + k), at(c0 + 2, r0 - 1 + k), tu);
            float detail = 0.0f, amp = 0.5f;
            double period = 4.0;
            for (int o = 0; o < 4; ++o, amp *= 1.6f, period *= 2)
                detail += amp * value_noise(c / period, r / period, std::uint32_t(o));
            out.z[std::size_t(r) * out.width + c] =
                catmull_rom(rows[0], rows[1], rows[2], rows[3], tv) + detail;
        }
    }
    return out;
}

// The width x height samples of `hf` starting at column c0, row r0 (clipped to the grid); the
// origin moves with the crop.
inline Heightfield crop(const Heightfield &hf, int width, int height, int c0 = 0, int r0 = 0) {
    Heightfield c = hf;
    c.width = std::min(width, hf.width - c0);
    c.height = std::min(height, hf.height - r0);
    c.origin_x = hf.origin_x + c0 * hf.dx;
    c.origin_y = hf.origin_y + r0 * hf.dy;
    c.z.resize(std::size_t(c.width) * c.height);
    for (int r = 0; r < c.height; ++r)
        for (int col = 0; col < c.width; ++col)
            c.at(col, r) = hf.at(c0 + col, r0 + r);
    c.void_mask.clear();
    return c;
}

// Twice the signed xy area of a triangle (positive: counter-clockwise seen from above).
inline double xy_area2(const Mesh::Point &a, const Mesh::Point &b, const Mesh::Point &c) {
    return double(b[0] - a[0]) * (c[1] - a[1]) - double(c[0] - a[0]) * (b[1] - a[1]);
}

// Live faces of a TIN whose xy area is <= 0 (fold-overs and slivers of zero area).
inline std::int64_t folded_faces(const Mesh &mesh) {
    std::int64_t n = 0;
    for (auto f : mesh.faces()) {
        if (mesh.status(f).deleted())
            continue;
        Mesh::Point p[3];
        int i = 0;
        for (auto v : f.vertices())
            p[i++] = mesh.point(v);
        n += xy_area2(p[0], p[1], p[2]) <= 0.0;
    }
    return n;
}

// ---- Triangles as grid sample ids (id = row * width + column) -----------------------------------

inline Mesh::Point grid_point(const Heightfield &hf, std::uint32_t id) {
    return Mesh::Point(float((id % hf.width) * hf.dx), float((id / hf.width) * hf.dy), 0.0f);
}

// Peer triangles come in either orientation: turn them counter-clockwise when most are clockwise.
inline void orient_ccw(const Heightfield &hf, std::vector<std::uint32_t> &tris) {
    std::int64_t negative = 0;
    for (std::size_t t = 0; t < tris.size(); t += 3)
        negative += xy_area2(grid_point(hf, tris[t]), grid_point(hf, tris[t + 1]),
                             grid_point(hf, tris[t + 2])) < 0.0;
    if (2 * negative > std::int64_t(tris.size() / 3))
        for (std::size_t t = 0; t < tris.size(); t += 3)
            std::swap(tris[t + 1], tris[t + 2]);
}

// Triangles whose xy area is <= 0: fold-overs and zero-area slivers.
inline std::int64_t folded_triangles(const Heightfield &hf,
                                     const std::vector<std::uint32_t> &tris) {
    std::int64_t n = 0;
    for (std::size_t t = 0; t < tris.size(); t += 3)
        n += xy_area2(grid_point(hf, tris[t]), grid_point(hf, tris[t + 1]),
                      grid_point(hf, tris[t + 2])) <= 0.0;
    return n;
}

// ---- Child processes ----------------------------------------------------------------------------

struct ProcessResult {
    std::string out;
    int status = 0;
    // Peak resident memory from wait4; a spawned child's count starts from this process's own peak
    // (the kernel carries it over at exec), so it is an upper bound of the child's.
    double peak_mb = 0.0;
    double wall_ms = 0.0; // spawn to exit, as the parent sees it: the whole process
    double cpu_ms = 0.0;  // its user + system CPU time
};

// Runs argv[0] with its arguments (PATH searched), stdout captured; stderr passes through (or, with
// `quiet`, goes to /dev/null). `core` >= 0 pins the process to that core, as `taskset -c CORE`
// would without an exec of its own. The child is spawned (posix_spawn: no copy of this process's
// page tables, whose cost would otherwise land in the child's time and grow with this process's
// size).
inline ProcessResult run_process(const std::vector<std::string> &argv, int core = -1,
                                 bool quiet = false) {
    int fd[2];
    if (pipe(fd) != 0)
        throw std::runtime_error("pipe failed");
    std::fflush(stdout);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addclose(&actions, fd[0]);
    posix_spawn_file_actions_adddup2(&actions, fd[1], 1);
    posix_spawn_file_actions_addclose(&actions, fd[1]);
    if (quiet)
        posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    std::vector<char *> args;
    for (const auto &a : argv)
        args.push_back(const_cast<char *>(a.c_str()));
    args.push_back(nullptr);
    // The child inherits the affinity of the thread that spawns it.
    cpu_set_t before;
    CPU_ZERO(&before);
    sched_getaffinity(0, sizeof before, &before);
    if (core >= 0) {
        cpu_set_t one;
        CPU_ZERO(&one);
        CPU_SET(core, &one);
        if (sched_setaffinity(0, sizeof one, &one) != 0)
            throw std::runtime_error("cannot run on core " + std::to_string(core));
    }
    Stopwatch clock;
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
    if (core >= 0)
        sched_setaffinity(0, sizeof before, &before);
    posix_spawn_file_actions_destroy(&actions);
    close(fd[1]);
    if (spawned != 0) {
        close(fd[0]);
        throw std::runtime_error(argv[0] + ": cannot run it: " + std::strerror(spawned));
    }
    ProcessResult result;
    char buffer[4096];
    for (ssize_t n; (n = read(fd[0], buffer, sizeof buffer)) > 0;)
        result.out.append(buffer, std::size_t(n));
    close(fd[0]);
    rusage usage{};
    wait4(pid, &result.status, 0, &usage);
    result.wall_ms = clock.ms();
    result.peak_mb = double(usage.ru_maxrss) / 1024.0;
    auto ms = [](const timeval &t) { return double(t.tv_sec) * 1e3 + double(t.tv_usec) / 1e3; };
    result.cpu_ms = ms(usage.ru_utime) + ms(usage.ru_stime);
    return result;
}

// ---- The npm heightmap meshers (peers/run_peers.mjs) --------------------------------------------

// The grid as the node peers read it: float32 heights, row-major, row 0 = south.
inline void write_grid_f32(const Heightfield &hf, const std::string &path) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char *>(hf.z.data()),
               std::streamsize(hf.z.size() * sizeof(float)));
}

struct NodePeerRun {
    nlohmann::json report;           // run_peers.mjs's line: ms, cpu_ms, max_error, ...
    std::vector<std::uint32_t> tris; // the last run's triangles, counter-clockwise
    double peak_mb = 0.0;            // Node's own peak
};

// The npm peers run_node_peer needs, checked before a bench starts: without them every peer row
// would fail one by one, deep in a run of many minutes.
inline void require_node_peers(const std::string &peers) {
    for (const char *package : {"delatin", "@mapbox/martini"})
        if (!std::filesystem::exists(peers + "/node_modules/" + package + "/package.json"))
            throw std::runtime_error(peers + ": npm package " + package +
                                     " is not installed (run `npm ci` there; `make bench` does)");
}

// delatin or martini through Node on the grid `grid_path` (write_grid_f32 of `hf`), `reps` times:
// mode "max_error" (value = the vertical bound) or "nodes" (value = the node count to reach).
inline NodePeerRun run_node_peer(const std::string &peers, const std::string &grid_path,
                                 const Heightfield &hf, const std::string &prefix,
                                 const std::string &tool, const std::string &mode, double value,
                                 int reps) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    const ProcessResult p =
        run_process({"node", peers + "/run_peers.mjs", grid_path, std::to_string(hf.width),
                     std::to_string(hf.height), prefix, tool, mode, text, std::to_string(reps)});
    if (p.status != 0 || p.out.empty())
        throw std::runtime_error(tool + " failed (status " + std::to_string(p.status) + ")");
    NodePeerRun run;
    run.report = nlohmann::json::parse(p.out);
    run.peak_mb = p.peak_mb;
    std::ifstream in(prefix + ".tri", std::ios::binary | std::ios::ate);
    run.tris.resize(std::size_t(in.tellg()) / 4);
    in.seekg(0);
    in.read(reinterpret_cast<char *>(run.tris.data()), std::streamsize(run.tris.size() * 4));
    std::filesystem::remove(prefix + ".tri");
    orient_ccw(hf, run.tris);
    return run;
}

// ---- Result rows --------------------------------------------------------------------------------

// A row's value as text: a top-level key, else the same key in its "extra" object; "" if absent.
inline std::string cell(const nlohmann::json &r, const std::string &key) {
    const bool top = r.contains(key) && !r[key].is_null();
    if (!top && !(r.contains("extra") && r["extra"].contains(key)))
        return "";
    const nlohmann::json &v = top ? r[key] : r["extra"][key];
    if (v.is_string())
        return v.get<std::string>();
    if (v.is_number_integer())
        return std::to_string(v.get<std::int64_t>());
    if (v.is_boolean())
        return v.get<bool>() ? "1" : "0";
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", v.get<double>());
    return text;
}

inline void write_csv(const std::string &path, const std::vector<std::string> &columns,
                      const std::vector<nlohmann::json> &rows) {
    std::ofstream out(path);
    for (std::size_t i = 0; i < columns.size(); ++i)
        out << (i ? "," : "") << columns[i];
    out << "\n";
    for (const nlohmann::json &r : rows) {
        for (std::size_t i = 0; i < columns.size(); ++i) {
            std::string v = cell(r, columns[i]);
            if (v.find_first_of(",\"") != std::string::npos)
                v = "\"" + v + "\"";
            out << (i ? "," : "") << v;
        }
        out << "\n";
    }
}

inline std::string fmt(const char *format, double v) {
    char text[64];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

} // namespace tinlod::bench
