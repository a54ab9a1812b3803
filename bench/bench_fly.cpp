// The flight benchmark (issue 6, "Performance"): one TIN (tinlod::Refiner) follows three camera
// paths, one after another, over a ~4k² terrain made from real data — a low drive along a valley, a
// fly-over, a descent from high above to the ground — at 4 frames per second of path time. The
// refiner is built once (the quad-tree retrieval at half the erase's bound, then the erase, from
// the first view; the samples the retrieval left out enter later by local edits); the jump from one
// path's end to the next one's start is an update kept apart from the frames. For each path, in one
// run:
//   - the per-frame update time (Refiner::update), p50 and p99, as CPU time of the one thread;
//   - the nodes each frame changed (erased + recovered), and how closely the time follows them
//     against how closely it follows the TIN size (Pearson r over the frames, and the partial r
//     with the other held fixed), with the least-squares line of time against nodes changed (its
//     time at zero change: a fixed cost);
//   - the bytes per input node of the whole structure (Refiner::bytes(): TIN + erase history);
//   - on every 20th frame (the 1st, 21st, ...) the paper's way from the same view, the TIN rebuilt
//     from scratch by retrieval at share * tau and node erase to tau over every sample (erase_dem,
//     as `tinlod simplify`, the quad-tree built once beforehand), with its time as a ratio to that
//     frame's update and both TINs' screen error measured exhaustively over every DEM sample
//     (measure_error), and the share of the heights the refiner's TIN needs in memory for its
//     bound from that view (height_working_set: what a refiner that paged its heights would keep).
// Each path's frames after the first stop once their updates took a time budget (the suite's 30
// minutes; the rebuilds and error measurements come on top); the results say how many of the
// path's frames were flown.
//
// Then each path at 30 frames per second, as an interactive viewer samples them (the camera moves
// 7.5 times less per frame), by a new refiner built at the path's first view, so that each flight
// is the refiner's first over its path: the update time per frame, p50 and p99, and the screen
// error measured exhaustively on every 150th frame; no rebuilds. Each path is then flown a second
// time by the refiner that has just flown it (after a jump back to its start, not counted): a
// refiner that has flown a path before changes far fewer nodes along it, as the erases it made on
// the way are the ones the way back undoes. And at 30 frames per second with the camera 2, 4 and
// 8 times slower (the same views as 60, 120 and 240 frames per second of path time), first
// flights again, so that the results say how fast an observer the refiner follows within the
// frame budget: the paths move the eye at 1-3 km/s.
//
// The paths come from the terrain's bounds and heights, the way scripts/make_paths.py makes
// meshes/paths/n42_*.csv: every keyframe's eye stands a clearance above the highest ground within
// 1.5 km, so no frame is under the terrain (each frame is checked with check_eye_above).
//
// Writes OUT/flight.csv (one line per frame), TMP/flight.dat (the series plot.gp draws) and
// TMP/flight.json (the headline claims and the RESULTS.md section, read by bench_suite --flight).
//
// usage: bench_fly --data DIR --out DIR --tmp DIR [--quick]
#include "tinlod/camera_path.hpp"
#include "tinlod/decimate.hpp"
#include "tinlod/metrics.hpp"
#include "tinlod/quadtree.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/refine.hpp"
#include "tinlod/store.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/util.hpp"
#include "tinlod/view.hpp"

#include "common.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace tinlod;
using json = nlohmann::json;

struct FlyOptions {
    std::string data; // ../shared/data (dem/N42E001.hgt)
    std::string out;  // bench/results
    std::string tmp;  // scratch: plot series, the summary for bench_suite
    bool quick = false;
};

constexpr double k_tau = 1.0;   // pixels, the refiner's and the rebuild's
constexpr double k_share = 0.5; // the rebuild retrieves at share * tau, erases to tau (erase_dem)
constexpr double k_fps = 4.0;   // frames per second of path time
constexpr double k_fps_interactive = 30.0; // the second flight's
constexpr int k_check_every = 150;         // its frames whose error is measured (1, 151, ...)
// The slowed flights' factors; each measures its error at the same path times as the 30 fps flight.
constexpr int k_slower[] = {2, 4, 8};
// The rebuild runs on every 20th frame: on 4097² it takes about 10 s (erase_dem's per-sample
// arrays and its mesh span the whole grid).
constexpr int k_rebuild_every = 20;
constexpr int k_block_cells = 16;       // the finer blocks a paging refiner could read heights by
constexpr int k_quick_frames = 21;      // the quick run flies at most the first 5 s of each path
constexpr double k_budget_s = 60;       // each path's updates stop once they took this long (wall,
constexpr double k_quick_budget_s = 10; // full / quick run); rebuilds and measurements not counted

double thread_cpu_ms() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) / 1e6;
}

double rss_mb() {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmRSS:", 0) == 0)
            return std::atof(line.c_str() + 6) / 1024.0;
    return 0.0;
}

std::string fmt(const char *format, double v) {
    char text[64];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

// ---- Camera paths from the terrain ------------------------------------------------------------

// Highest sample within `radius` of local (x, y), clipped to the grid.
double ground_max(const Heightfield &hf, double x, double y, double radius) {
    const int c0 = std::max(0, int(std::floor((x - radius) / hf.dx)));
    const int c1 = std::min(hf.width - 1, int(std::ceil((x + radius) / hf.dx)));
    const int r0 = std::max(0, int(std::floor((y - radius) / hf.dy)));
    const int r1 = std::min(hf.height - 1, int(std::ceil((y + radius) / hf.dy)));
    double best = -1e30;
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c)
            best = std::max(best, double(hf.at(c, r)));
    return best;
}

// make_paths.py's drive: `steps` + 1 keyframes over `seconds` on the straight line start -> end,
// the eye `clearance` above the highest ground within 1.5 km, looking `look_ahead` metres ahead
// and `look_down` metres down.
CameraPath drive(const Heightfield &hf, glm::dvec2 start, glm::dvec2 end, double clearance,
                 double look_ahead, double look_down, double seconds, int steps) {
    const glm::dvec2 dir = glm::normalize(end - start);
    CameraPath path;
    for (int i = 0; i <= steps; ++i) {
        const double s = double(i) / steps;
        const glm::dvec2 p = start + (end - start) * s;
        const double z = ground_max(hf, p.x, p.y, 1500.0) + clearance;
        const glm::dvec2 a = p + dir * look_ahead;
        path.keys.push_back({seconds * s, {p.x, p.y, z}, {a.x, a.y, z - look_down}});
    }
    return path;
}

struct FlightPath {
    std::string name;
    std::string description;
    CameraPath path;
};

// The three paths over `hf`. The valley is the deepest of 100 candidate straight drives (0.3 of
// the extent long, 4 headings, 25 centres in the middle 0.3-0.7 of the bounds): the one whose
// ground lies lowest below the ground 0.02 of the extent to either side.
std::vector<FlightPath> flight_paths(const Heightfield &hf) {
    const double w = (hf.width - 1) * hf.dx, h = (hf.height - 1) * hf.dy, extent = std::max(w, h);
    std::vector<FlightPath> paths;

    const double length = 0.3 * extent, side = 0.02 * extent;
    double deepest = 1e30;
    glm::dvec2 start{0.0}, end{0.0};
    for (int heading = 0; heading < 4; ++heading) {
        const double angle = heading * M_PI / 4;
        const glm::dvec2 dir{std::cos(angle), std::sin(angle)}, normal{-dir.y, dir.x};
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j) {
                const glm::dvec2 centre{w * (0.3 + 0.1 * i), h * (0.3 + 0.1 * j)};
                double depth = 0.0;
                for (int k = 0; k <= 20; ++k) {
                    const glm::dvec2 p = centre + dir * (length * (k / 20.0 - 0.5));
                    const glm::dvec2 l = p + normal * side, r = p - normal * side;
                    depth += ground_max(hf, p.x, p.y, 0.0) -
                             0.5 * (ground_max(hf, l.x, l.y, 0.0) + ground_max(hf, r.x, r.y, 0.0));
                }
                if (depth < deepest) {
                    deepest = depth;
                    start = centre - dir * (length / 2);
                    end = centre + dir * (length / 2);
                }
            }
    }
    paths.push_back({"valley",
                     "low drive along the deepest valley found, from (" +
                         fmt("%.1f", start.x / 1e3) + ", " + fmt("%.1f", start.y / 1e3) + ") to (" +
                         fmt("%.1f", end.x / 1e3) + ", " + fmt("%.1f", end.y / 1e3) +
                         ") km, 150 m above the highest ground within 1.5 km, looking 4 km ahead "
                         "and 400 m down; 20 s",
                     drive(hf, start, end, 150.0, 4000.0, 400.0, 20.0, 20)});

    paths.push_back(
        {"flyover",
         "south to north over the middle, 2.5 km above the highest ground within "
         "1.5 km, looking 12 km ahead and 4 km down; 30 s",
         drive(hf, {0.49 * w, 0.07 * h}, {0.51 * w, 0.9 * h}, 2500.0, 12000.0, 4000.0, 30.0, 30)});

    // Altitude falls exponentially from half the extent above the highest point to 300 m above
    // the highest ground within 1.5 km of the last eye, while the eye drifts toward the centre.
    const glm::dvec2 centre{0.5 * w, 0.5 * h};
    const glm::dvec2 from = centre - glm::dvec2{0.0, 0.045 * extent};
    const glm::dvec2 to = centre - glm::dvec2{0.027 * extent, 0.027 * extent};
    const double high = hf.max_z() + 0.5 * extent;
    const double low = ground_max(hf, to.x, to.y, 1500.0) + 300.0;
    const double focus = ground_max(hf, centre.x, centre.y, 0.0);
    CameraPath descent;
    for (int i = 0; i <= 20; ++i) {
        const double s = i / 20.0;
        const glm::dvec2 p = from + (to - from) * s;
        descent.keys.push_back({20.0 * s,
                                {p.x, p.y, std::exp(std::log(high) * (1 - s) + std::log(low) * s)},
                                {centre.x, centre.y, focus}});
    }
    paths.push_back({"descent",
                     "from half the extent above the highest point (" + fmt("%.0f", high) +
                         " m) down to 300 m above the ground, looking at the centre; 20 s",
                     std::move(descent)});
    return paths;
}

// ---- Flying -----------------------------------------------------------------------------------

struct FrameRow {
    int frame = 0;
    double t = 0.0;
    double ms = 0.0;     // wall time of Refiner::update
    double cpu_ms = 0.0; // CPU time of the thread in it
    FrameStats stats;
    double bytes_per_node = 0.0;
    bool checked = false; // max_px measured (the interactive flight's every k_check_every-th)
    bool rebuilt = false; // the rest only on the rebuild frames
    double rebuild_ms = 0.0, rebuild_cpu_ms = 0.0;
    std::int64_t rebuild_nodes = 0, rebuild_triangles = 0;
    double max_px = 0.0, rebuild_max_px = 0.0;
    // The share of the heights the refiner's TIN needs for its bound from the frame's view
    // (height_working_set): of the store's tiles, and of 16-cell blocks (rebuild frames).
    double heights_tiles = 0.0, heights_blocks = 0.0;
    std::int64_t changed() const { return stats.update.erased + stats.update.recovered; }
};

struct PathResult {
    std::string name, description;
    bool built = false;         // frame 0 built the refiner (else: the jump from the last path)
    double first_ms = 0.0;      // frame 0: the constructor (retrieval + erase) or the jump
    double first_max_px = 0.0;  // its measured error
    double bytes_mb = 0.0;      // Refiner::bytes() after the path's last frame
    std::vector<FrameRow> rows; // frames 1.. (frame 0 is kept apart)
    int planned = 0;            // updates the path holds (rows.size() < planned: budget ran out)
};

struct Flight {
    std::vector<PathResult> paths;
    std::vector<PathResult> interactive; // the same paths at k_fps_interactive, first flights
    std::vector<PathResult> repeated;    // each flown again right after its first flight
    std::vector<std::vector<PathResult>> slowed; // and with the camera k_slower[i] times slower
    std::vector<double> eye_speed;               // each path's mean eye speed, m/s
    double built_bytes_mb = 0.0;                 // Refiner::bytes() right after the constructor
    double built_rss_mb = 0.0;                   // resident memory the constructor added
    std::int64_t samples = 0;                    // the terrain's
};

double measured_px(const Heightfield &hf, const Mesh &tin, const View &view) {
    ErrorOptions eo;
    eo.view = &view;
    return measure_error(hf, tin, eo).max_screen_px;
}

// Flies path p at `fps` frames per second of path time, the camera `slower` times slower than
// the path (the views of fps * slower frames per second); frame 0 builds `refiner` when it is
// null, else moves it there by one update. `rebuilds`: the paper's way on every
// k_rebuild_every-th frame, else the error measured on every (k_check_every * slower)-th.
PathResult fly(const Heightfield &hf, const QuadTree &tree, const FlightPath &p, bool quick,
               double fps, bool rebuilds, std::unique_ptr<Refiner> &refiner, Flight &flight,
               int slower = 1) {
    const int all = int(std::floor(p.path.duration() * slower * fps + 1e-9)) + 1;
    const int check_every = k_check_every * slower;
    std::vector<View> views = p.path.sample(all, View{});
    if (quick)
        views.resize(std::min<std::size_t>(views.size(), k_quick_frames));
    for (const View &v : views) {
        validate(v, p.name);
        check_eye_above(hf, v.eye, p.name);
    }
    PathResult result;
    result.name = p.name;
    result.description = p.description;
    result.planned = int(views.size()) - 1;
    result.built = !refiner;
    std::printf("  %-8s %3zu frames: %s ", p.name.c_str(), views.size(),
                result.built ? "built" : "jump");
    std::fflush(stdout);

    Stopwatch clock;
    if (result.built) {
        RefineOptions options;
        options.tolerance = k_tau;
        const double rss0 = rss_mb();
        refiner = std::make_unique<Refiner>(hf, views.front(), options);
        result.first_ms = clock.ms();
        if (flight.paths.empty()) { // the first refiner's, built on a fresh process's heap
            flight.built_rss_mb = rss_mb() - rss0;
            flight.built_bytes_mb = double(refiner->bytes()) / (1024.0 * 1024.0);
        }
    } else {
        refiner->update(views.front());
        result.first_ms = clock.ms();
    }
    result.first_max_px = measured_px(hf, refiner->mesh(), views.front());
    std::printf("%.1f s; updates ", result.first_ms / 1e3);
    std::fflush(stdout);

    EraseOptions eo;
    eo.tolerance = k_tau;
    DemEraseOptions rebuild;
    rebuild.retrieve_share = k_share;
    rebuild.tree = &tree;
    const double budget_ms = (quick ? k_quick_budget_s : k_budget_s) * 1e3;
    double flying_ms = 0.0; // the updates' wall time
    for (std::size_t i = 1; i < views.size() && flying_ms < budget_ms; ++i) {
        FrameRow row;
        row.frame = int(i);
        row.t = p.path.keys.front().t + slower * p.path.duration() * double(i) / double(all - 1);
        const double cpu0 = thread_cpu_ms();
        clock.reset();
        row.stats = refiner->update(views[i]);
        row.ms = clock.ms();
        row.cpu_ms = thread_cpu_ms() - cpu0;
        flying_ms += row.ms;
        row.bytes_per_node = double(refiner->bytes()) / double(hf.size());
        if (!rebuilds && i % check_every == 1) {
            row.checked = true;
            row.max_px = measured_px(hf, refiner->mesh(), views[i]);
            std::printf("m");
        } else if (rebuilds && i % k_rebuild_every == 1) {
            const double rcpu0 = thread_cpu_ms();
            clock.reset();
            const Mesh rebuilt = erase_dem(hf, &views[i], eo, rebuild);
            row.rebuild_ms = clock.ms();
            row.rebuild_cpu_ms = thread_cpu_ms() - rcpu0;
            row.rebuilt = true;
            row.rebuild_nodes = std::int64_t(rebuilt.n_vertices());
            row.rebuild_triangles = std::int64_t(rebuilt.n_faces());
            row.max_px = measured_px(hf, refiner->mesh(), views[i]);
            row.rebuild_max_px = measured_px(hf, rebuilt, views[i]);
            const SignificanceOptions weights = RefineOptions{}.significance;
            row.heights_tiles =
                height_working_set(tree, refiner->mesh(), views[i], weights, k_tau,
                                   level_for_cells(tree.layout(), k_store_tile_cells))
                    .share();
            row.heights_blocks = height_working_set(tree, refiner->mesh(), views[i], weights, k_tau,
                                                    level_for_cells(tree.layout(), k_block_cells))
                                     .share();
            std::printf("r");
        } else {
            std::printf(".");
        }
        std::fflush(stdout);
        result.rows.push_back(row);
    }
    result.bytes_mb = double(refiner->bytes()) / (1024.0 * 1024.0);
    std::printf(" %zu of %d updates in %.0f s\n", result.rows.size(), result.planned,
                flying_ms / 1e3);
    return result;
}

// ---- Figures ----------------------------------------------------------------------------------

// Nearest-rank percentile (as `tinlod fly` prints it).
double percentile(std::vector<double> v, double q) {
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5))];
}

// Means and centred sums of squares and products of paired samples.
struct Moments {
    double mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
};

Moments moments(const std::vector<double> &x, const std::vector<double> &y) {
    const double n = double(x.size());
    Moments m;
    for (std::size_t i = 0; i < x.size(); ++i) {
        m.mx += x[i] / n;
        m.my += y[i] / n;
    }
    for (std::size_t i = 0; i < x.size(); ++i) {
        m.sxy += (x[i] - m.mx) * (y[i] - m.my);
        m.sxx += (x[i] - m.mx) * (x[i] - m.mx);
        m.syy += (y[i] - m.my) * (y[i] - m.my);
    }
    return m;
}

double pearson(const std::vector<double> &x, const std::vector<double> &y) {
    const Moments m = moments(x, y);
    return m.sxx > 0 && m.syy > 0 ? m.sxy / std::sqrt(m.sxx * m.syy) : 0.0;
}

// The partial correlation of x and y with z held fixed, from the three Pearson r: how closely x
// follows y once what z explains of both is taken out (0 when z explains either whole).
double partial(double r_xy, double r_xz, double r_yz) {
    const double d = (1.0 - r_xz * r_xz) * (1.0 - r_yz * r_yz);
    return d > 0 ? (r_xy - r_xz * r_yz) / std::sqrt(d) : 0.0;
}

// Least-squares line y = intercept + slope * x.
struct Line {
    double intercept = 0.0, slope = 0.0;
};

Line fit(const std::vector<double> &x, const std::vector<double> &y) {
    const Moments m = moments(x, y);
    const double slope = m.sxx > 0 ? m.sxy / m.sxx : 0.0;
    return {m.my - slope * m.mx, slope};
}

struct Summary {
    double p50 = 0, p99 = 0, max = 0, wall_p50 = 0, wall_p99 = 0;
    double changed_median = 0, changed_max = 0, nodes_min = 0, nodes_max = 0;
    double r_changed = 0, r_nodes = 0;
    // The same with the other held fixed: a path whose TIN grows as its changes do (the fly-over)
    // shows both raw r high.
    double pr_changed = 0, pr_nodes = 0;
    double fixed_ms = 0, us_per_changed = 0; // update CPU ms = fixed + us/1000 * changed (fit)
    double bytes_per_node = 0;               // the largest over the frames
    int rebuilds = 0;
    double rebuild_cpu_median = 0, ratio_median = 0, ratio_min = 0;
    double max_px = 0, rebuild_max_px = 0; // over the rebuild (or checked) frames
    int checks = 0;
    // The shares of the heights the TIN's bound needs (FrameRow), least and most over the rebuild
    // frames.
    double tiles_min = 1, tiles_max = 0, blocks_min = 1, blocks_max = 0;
};

Summary summarise(const std::vector<FrameRow> &rows) {
    Summary s;
    std::vector<double> cpu, wall, changed, nodes, rebuild_cpu, ratio;
    for (const FrameRow &r : rows) {
        cpu.push_back(r.cpu_ms);
        wall.push_back(r.ms);
        changed.push_back(double(r.changed()));
        nodes.push_back(double(r.stats.nodes));
        s.bytes_per_node = std::max(s.bytes_per_node, r.bytes_per_node);
        if (r.checked) {
            ++s.checks;
            s.max_px = std::max(s.max_px, r.max_px);
        }
        if (!r.rebuilt)
            continue;
        ++s.rebuilds;
        rebuild_cpu.push_back(r.rebuild_cpu_ms);
        ratio.push_back(r.rebuild_cpu_ms / std::max(1e-3, r.cpu_ms));
        s.max_px = std::max(s.max_px, r.max_px);
        s.rebuild_max_px = std::max(s.rebuild_max_px, r.rebuild_max_px);
        s.tiles_min = std::min(s.tiles_min, r.heights_tiles);
        s.tiles_max = std::max(s.tiles_max, r.heights_tiles);
        s.blocks_min = std::min(s.blocks_min, r.heights_blocks);
        s.blocks_max = std::max(s.blocks_max, r.heights_blocks);
    }
    if (rows.empty())
        return s;
    s.p50 = percentile(cpu, 0.5);
    s.p99 = percentile(cpu, 0.99);
    s.max = percentile(cpu, 1.0);
    s.wall_p50 = percentile(wall, 0.5);
    s.wall_p99 = percentile(wall, 0.99);
    s.changed_median = percentile(changed, 0.5);
    s.changed_max = percentile(changed, 1.0);
    s.nodes_min = percentile(nodes, 0.0);
    s.nodes_max = percentile(nodes, 1.0);
    s.r_changed = pearson(cpu, changed);
    s.r_nodes = pearson(cpu, nodes);
    const double r_both = pearson(changed, nodes);
    s.pr_changed = partial(s.r_changed, s.r_nodes, r_both);
    s.pr_nodes = partial(s.r_nodes, s.r_changed, r_both);
    const Line line = fit(changed, cpu);
    s.fixed_ms = line.intercept;
    s.us_per_changed = line.slope * 1e3;
    if (s.rebuilds > 0) {
        s.rebuild_cpu_median = percentile(rebuild_cpu, 0.5);
        s.ratio_median = percentile(ratio, 0.5);
        s.ratio_min = percentile(ratio, 0.0);
    }
    return s;
}

// ---- Output -----------------------------------------------------------------------------------

// Samples the first frame's retrieval left out that the path's updates brought in.
std::int64_t entered(const PathResult &p) {
    std::int64_t n = 0;
    for (const FrameRow &r : p.rows)
        n += r.stats.update.entered;
    return n;
}

// One line per frame of the flights at 4 and 30 fps (fps tells them apart); the slowed flights'
// 30,000 frames are summed up in the section only.
void write_csv(const std::string &file, const Flight &flight) {
    std::ofstream out(file);
    out << "path,fps,frame,t,ms,cpu_ms,changed,erased,recovered,reerased,entered,candidates,nodes,"
           "triangles,"
           "bytes_per_node,rebuild_ms,rebuild_cpu_ms,rebuild_nodes,rebuild_triangles,"
           "rebuild_ratio,max_screen_px,rebuild_max_screen_px,heights_tiles_share,"
           "heights_blocks_share\n";
    for (const auto &[fps, results] :
         {std::pair{k_fps, &flight.paths}, std::pair{k_fps_interactive, &flight.interactive}})
        for (const PathResult &p : *results)
            for (const FrameRow &r : p.rows) {
                out << p.name << "," << fmt("%.0f", fps) << "," << r.frame << ","
                    << fmt("%.3f", r.t) << "," << fmt("%.4f", r.ms) << "," << fmt("%.4f", r.cpu_ms)
                    << "," << r.changed() << "," << r.stats.update.erased << ","
                    << r.stats.update.recovered << "," << r.stats.update.reerased << ","
                    << r.stats.update.entered << "," << r.stats.update.candidates << ","
                    << r.stats.nodes << "," << r.stats.triangles << ","
                    << fmt("%.2f", r.bytes_per_node) << ",";
                if (r.rebuilt)
                    out << fmt("%.2f", r.rebuild_ms) << "," << fmt("%.2f", r.rebuild_cpu_ms) << ","
                        << r.rebuild_nodes << "," << r.rebuild_triangles << ","
                        << fmt("%.1f", r.rebuild_cpu_ms / std::max(1e-3, r.cpu_ms)) << ","
                        << fmt("%.4f", r.max_px) << "," << fmt("%.4f", r.rebuild_max_px) << ","
                        << fmt("%.4f", r.heights_tiles) << "," << fmt("%.4f", r.heights_blocks);
                else if (r.checked)
                    out << ",,,,," << fmt("%.4f", r.max_px) << ",,,";
                else
                    out << ",,,,,,,,";
                out << "\n";
            }
}

// gnuplot series: one block per path (title line first): changed, TIN nodes, CPU ms.
void write_series(const std::string &file, const std::vector<PathResult> &results) {
    std::ofstream out(file);
    for (const PathResult &p : results) {
        if (&p != &results.front())
            out << "\n\n"; // between blocks only: a trailing one would count as an empty block
        out << "\"" << p.name << "\" \"\" \"\"\n";
        for (const FrameRow &r : p.rows)
            out << r.changed() << " " << r.stats.nodes << " " << r.cpu_ms << "\n";
    }
}

struct Claim {
    std::string claim, measured, verdict;
};

// "N of M frames flown" when the budget cut a path short, else "".
std::string flown(const PathResult &p) {
    return int(p.rows.size()) < p.planned ? " (" + std::to_string(p.rows.size()) + " of " +
                                                std::to_string(p.planned) + " updates: budget)"
                                          : "";
}

// The p99 ≤ 8 ms claim over one flight's paths.
Claim p99_claim(const std::string &claim, const std::vector<PathResult> &results,
                const std::vector<Summary> &sums) {
    std::string text;
    double worst = 0.0;
    for (std::size_t i = 0; i < results.size(); ++i) {
        text += (i ? "; " : "") + results[i].name + " p50 " + fmt("%.2f", sums[i].p50) +
                " ms, p99 " + fmt("%.2f", sums[i].p99) + " ms" + flown(results[i]);
        worst = std::max(worst, sums[i].p99);
    }
    return {claim, text,
            worst <= 8 ? "ahead by " + fmt("%.1f×", 8 / worst)
                       : "behind: p99 " + fmt("%.1f", worst) + " ms = " + fmt("%.1f×", worst / 8) +
                             " the goal"};
}

// "1/k" for a camera k times slower than the paths, "1" for the paths' own speed.
std::string speed_name(int slower) { return slower == 1 ? "1" : "1/" + std::to_string(slower); }

// How many times slower than the paths the camera of ssums[k] below flies (k = 0: the 30 fps
// flight at the paths' own speed).
int slower_of(std::size_t k) { return k == 0 ? 1 : k_slower[k - 1]; }

// The p99 ≤ 8 ms claim at 30 fps against the camera's speed: the fastest of the speeds flown
// (the paths' own and the slowed ones) from which on every slower one keeps every path's p99 within
// the goal. ssums[0] is the 30 fps flight's, ssums[k] the one k_slower[k - 1] times slower.
Claim speed_claim(const Flight &flight, const std::vector<std::vector<Summary>> &ssums) {
    std::string text;
    int holds_from = 0; // slowest first: the factor from which every slower speed holds
    for (std::size_t k = ssums.size(); k-- > 0;) {
        bool all = true;
        for (const Summary &s : ssums[k])
            all = all && s.p99 <= 8;
        if (!all)
            break;
        holds_from = slower_of(k);
    }
    for (std::size_t k = 0; k < ssums.size(); ++k) {
        text += (k ? "; " : "") + speed_name(slower_of(k)) + ": p99";
        for (std::size_t i = 0; i < ssums[k].size(); ++i)
            text += (i ? " / " : " ") + fmt("%.1f", ssums[k][i].p99);
        text += " ms";
    }
    std::string names, speeds;
    for (std::size_t i = 0; i < flight.interactive.size(); ++i) {
        names += (i ? " / " : "") + flight.interactive[i].name;
        speeds += (i ? " / " : "") + fmt("%.0f", flight.eye_speed[i] / std::max(1, holds_from));
    }
    text += " (" + names + ")";
    return {"flight p99 ≤ 8 ms at " + fmt("%.0f", k_fps_interactive) +
                " frames per second against the camera's speed (the paths flown at their own "
                "speed and 2, 4 and 8 times slower, each the first flight of a new refiner)",
            text,
            holds_from == 0
                ? "behind at every speed flown"
                : "holds at " + speed_name(holds_from) +
                      " of the paths' speed and slower (mean eye speed " + speeds + " m/s there)"};
}

std::vector<Claim> claims(const Flight &flight, const std::vector<Summary> &sums,
                          const Summary &pooled, const std::vector<Summary> &isums,
                          const std::vector<std::vector<Summary>> &ssums) {
    const std::vector<PathResult> &results = flight.paths;
    std::vector<Claim> out;
    out.push_back(p99_claim("flight p99 ≤ 8 ms (Refiner::update per frame, CPU time of one core, "
                            "worst path; " +
                                fmt("%.0f", k_fps) + " frames per second of path time)",
                            results, sums));
    out.push_back(p99_claim("flight p99 ≤ 8 ms at " + fmt("%.0f", k_fps_interactive) +
                                " frames per second (the same paths as an interactive viewer "
                                "samples them, each the first flight of a new refiner)",
                            flight.interactive, isums));
    out.push_back(speed_claim(flight, ssums));
    std::string text;
    double lowest_median = 1e30, lowest = 1e30, flight_px = 0, rebuild_px = 0;
    int below = 0, frames = 0;
    for (std::size_t i = 0; i < results.size(); ++i) {
        if (sums[i].rebuilds == 0)
            continue;
        text += (text.empty() ? "" : "; ") + results[i].name + " median " +
                fmt("%.0f×", sums[i].ratio_median) + " (lowest " + fmt("%.0f×", sums[i].ratio_min) +
                ")";
        lowest_median = std::min(lowest_median, sums[i].ratio_median);
        lowest = std::min(lowest, sums[i].ratio_min);
        flight_px = std::max(flight_px, sums[i].max_px);
        rebuild_px = std::max(rebuild_px, sums[i].rebuild_max_px);
        for (const FrameRow &r : results[i].rows)
            if (r.rebuilt) {
                ++frames;
                below += r.rebuild_cpu_ms < 10 * r.cpu_ms;
            }
    }
    if (frames > 0)
        out.push_back(
            {"flight ≥ 10× faster than rebuild per frame (retrieval at " + fmt("%.1f", k_share) +
                 " τ + erase to τ over every sample, τ = " + fmt("%.0f", k_tau) +
                 " px, same view, every " + std::to_string(k_rebuild_every) +
                 "th frame; median ratio of CPU times)",
             text + "; measured max error: flight " + fmt("%.3f", flight_px) + " px, rebuild " +
                 fmt("%.3f", rebuild_px) + " px" +
                 (rebuild_px > k_tau ? " (the rebuild shows more error than τ: the ratio "
                                       "flatters the rebuild)"
                                     : ""),
             lowest >= 10 ? "ahead by " + fmt("%.0f×", lowest / 10) + " on every frame"
             : lowest_median >= 10
                 ? "ahead on the median; behind on " + std::to_string(below) + " of " +
                       std::to_string(frames) + " frames (lowest " + fmt("%.1f×", lowest) + ")"
                 : "behind: lowest path median " + fmt("%.1f×", lowest_median)});

    text.clear();
    double most = 0.0;
    for (std::size_t i = 0; i < results.size(); ++i) {
        text +=
            (i ? "; " : "") + results[i].name + " " + fmt("%.0f", sums[i].bytes_per_node) + " B";
        most = std::max(most, sums[i].bytes_per_node);
    }
    out.push_back(
        {"flight ≤ 100 B per node (Refiner::bytes(): TIN + erase history, per input node; "
         "the largest over the frames)",
         text,
         most <= 100
             ? "ahead by " + fmt("%.2f×", 100 / most)
             : "behind: " + fmt("%.0f", most) + " B = " + fmt("%.2f×", most / 100) + " the goal"});

    // Time follows the change when, with the TIN size held fixed, it correlates with the change
    // more than with the TIN size with the change held fixed (partial r: the raw r of a path whose
    // TIN grows with its changes credits each with the other's share), on every path at both
    // rates; and the part no change explains (the fit's time at zero nodes changed) is at most
    // half the median.
    text.clear();
    std::string against;
    const auto rates = [&](double fps, const std::vector<PathResult> &paths,
                           const std::vector<Summary> &ss) {
        const std::string rate = fmt("%.0f", fps) + " fps";
        text += (text.empty() ? "" : "; ") + rate + ":";
        for (std::size_t i = 0; i < paths.size(); ++i) {
            text += (i ? "; " : " ") + paths[i].name + " " + fmt("%.2f", ss[i].pr_changed) +
                    " vs " + fmt("%.2f", ss[i].pr_nodes) + " (raw " + fmt("%.2f", ss[i].r_changed) +
                    " vs " + fmt("%.2f", ss[i].r_nodes) + ")";
            if (!(ss[i].pr_changed > ss[i].pr_nodes))
                against += (against.empty() ? "" : ", ") + paths[i].name + " at " + rate;
        }
    };
    rates(k_fps, results, sums);
    rates(k_fps_interactive, flight.interactive, isums);
    text += "; fit over all " + fmt("%.0f", k_fps) +
            " fps frames: " + fmt("%.0f", pooled.fixed_ms) + " ms per frame + " +
            fmt("%.2f", pooled.us_per_changed) + " µs per node changed (p50 " +
            fmt("%.0f", pooled.p50) + " ms)";
    const double fixed_share = pooled.fixed_ms / std::max(1e-9, pooled.p50);
    out.push_back(
        {"flight time follows the nodes changed, not the TIN size (partial r of update "
         "time with nodes changed, TIN nodes held fixed, vs with TIN nodes, nodes "
         "changed held fixed; the time the fit gives at zero nodes changed ≤ half the "
         "p50)",
         text,
         !against.empty()    ? "behind on " + against + ": there the TIN size correlates more"
         : fixed_share > 0.5 ? "behind: correlates with the change on every path, but " +
                                   fmt("%.0f%%", 100 * fixed_share) +
                                   " of the p50 is a fixed cost per frame that no change explains"
                             : "holds on every path"});
    return out;
}

std::string section(const Flight &flight, const std::vector<Summary> &sums, const Summary &pooled,
                    const std::vector<Summary> &isums,
                    const std::vector<std::vector<Summary>> &ssums, const std::string &terrain,
                    bool quick) {
    const std::vector<PathResult> &results = flight.paths;
    std::string md =
        "\n## Flight (flight.csv)\n\n![update time against nodes changed and TIN size](flight.png)"
        "\n\nOne `Refiner` (τ = " +
        fmt("%.0f", k_tau) + " px, hysteresis 0.25, screen model) over " + terrain +
        " flies the three paths one after another at " + fmt("%.0f", k_fps) +
        " frames per second of path time" +
        (quick ? " (QUICK run: at most the first " + std::to_string(k_quick_frames) +
                     " frames of each path)"
               : std::string()) +
        ". Frame 0 of the first path builds it (the quad-tree retrieval at half the erase's bound, "
        "then the erase, from that view; the samples the retrieval left out enter by local edits "
        "where the paths come close: *entered*); frame 0 of the others is the jump from the last "
        "path's end, one update; both are listed apart, not among the frames. Update time = CPU "
        "time of the one thread inside `Refiner::update` "
        "(wall p50/p99 beside it: the machine is shared); changed = erased + recovered nodes; r = "
        "Pearson correlation of the update time with the nodes changed and with the TIN's live "
        "nodes over the frames, and in brackets the partial r, with the other held fixed; fixed ms "
        "+ µs per changed node = the least-squares line of the "
        "update time against the nodes changed. Bytes per node = `Refiner::bytes()` / input "
        "nodes, the largest over the path's frames; right after the constructor bytes() counted " +
        fmt("%.0f", flight.built_bytes_mb) + " MB and the resident memory grew by " +
        fmt("%.0f", flight.built_rss_mb) + " MB. Each path's updates stop once they took " +
        fmt("%.0f", quick ? k_quick_budget_s : k_budget_s) +
        " s of wall time (the rebuilds and error measurements not counted), so that `make bench` "
        "stays within 30 minutes: *updates* says how many "
        "of the path's updates were flown.\n\nPaths (from the terrain's bounds and heights; every "
        "eye checked above the ground):\n\n";
    for (const PathResult &p : results)
        md += "- **" + p.name + "**: " + p.description + "\n";
    md +=
        "\n| path | updates | frame 0 s | update CPU ms p50 / p99 / max | wall ms p50 / p99 | "
        "changed per frame median (max) | entered in all | TIN nodes min–max | r(time, changed) | "
        "r(time, nodes) | fixed ms + µs per changed node | bytes per node | bytes() MB at the "
        "end |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
        const Summary &s = sums[i];
        const PathResult &p = results[i];
        md += "| " + p.name + " | " + std::to_string(p.rows.size()) + " of " +
              std::to_string(p.planned) + " | " + fmt("%.1f", p.first_ms / 1e3) +
              (p.built ? " (built)" : " (jump)") + " | " + fmt("%.2f", s.p50) + " / " +
              fmt("%.2f", s.p99) + " / " + fmt("%.2f", s.max) + " | " + fmt("%.2f", s.wall_p50) +
              " / " + fmt("%.2f", s.wall_p99) + " | " + fmt("%.0f", s.changed_median) + " (" +
              fmt("%.0f", s.changed_max) + ") | " + std::to_string(entered(p)) + " | " +
              fmt("%.0f", s.nodes_min) + "–" + fmt("%.0f", s.nodes_max) + " | " +
              fmt("%.2f", s.r_changed) + " (" + fmt("%.2f", s.pr_changed) + ") | " +
              fmt("%.2f", s.r_nodes) + " (" + fmt("%.2f", s.pr_nodes) + ") | " +
              fmt("%.0f", s.fixed_ms) + " + " + fmt("%.2f", s.us_per_changed) + " | " +
              fmt("%.0f", s.bytes_per_node) + " | " + fmt("%.0f", p.bytes_mb) + " |\n";
    }
    md += "| all | | | " + fmt("%.2f", pooled.p50) + " / " + fmt("%.2f", pooled.p99) + " / " +
          fmt("%.2f", pooled.max) + " | " + fmt("%.2f", pooled.wall_p50) + " / " +
          fmt("%.2f", pooled.wall_p99) + " | " + fmt("%.0f", pooled.changed_median) + " (" +
          fmt("%.0f", pooled.changed_max) + ") | | | " + fmt("%.2f", pooled.r_changed) + " (" +
          fmt("%.2f", pooled.pr_changed) + ") | " + fmt("%.2f", pooled.r_nodes) + " (" +
          fmt("%.2f", pooled.pr_nodes) + ") | " + fmt("%.0f", pooled.fixed_ms) + " + " +
          fmt("%.2f", pooled.us_per_changed) + " | | |\n";
    md +=
        "\nAgainst the paper's way on every " + std::to_string(k_rebuild_every) +
        "th frame (frames 1, " + std::to_string(k_rebuild_every + 1) +
        ", ...): the TIN rebuilt from scratch from the same view by quad-tree retrieval at " +
        fmt("%.1f", k_share) +
        " τ and node erase to τ over every sample of the grid (`tinlod simplify --retrieve-share " +
        fmt("%.1f", k_share) +
        "`; the quad-tree built once beforehand, untimed). Ratio = rebuild CPU "
        "time / that frame's update CPU time. Both TINs' screen error measured exhaustively over "
        "every DEM sample inside the frustum; frame 0's flight error is in the last column.\n\n"
        "| path | rebuild frames | rebuild CPU ms median | rebuild nodes (last) | ratio median "
        "(lowest) | flight max px | rebuild max px | frame 0 px |\n"
        "|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
        const Summary &s = sums[i];
        std::int64_t nodes = 0;
        for (const FrameRow &r : results[i].rows)
            if (r.rebuilt)
                nodes = r.rebuild_nodes;
        md += "| " + results[i].name + " | " + std::to_string(s.rebuilds) + " | " +
              fmt("%.0f", s.rebuild_cpu_median) + " | " + std::to_string(nodes) + " | " +
              fmt("%.0f×", s.ratio_median) + " (" + fmt("%.0f×", s.ratio_min) + ") | " +
              fmt("%.3f", s.max_px) + " | " + fmt("%.3f", s.rebuild_max_px) + " | " +
              fmt("%.3f", results[i].first_max_px) + " |\n";
    }
    md += "\nThe heights the refiner keeps in memory, all of them (" +
          fmt("%.0f", double(flight.samples) * sizeof(float) / (1024.0 * 1024.0)) +
          " MB here): which of them would a refiner that paged them need, on those same frames? "
          "Those under a face whose deviation from it the quad-tree's node bounds cannot clear "
          "(`height_working_set`: a node's bound plus its fan's distance from the face's plane, "
          "times the largest weight over the node, within τ), by blocks of heights: the store's "
          "tiles (" +
          std::to_string(k_store_tile_cells) + " cells a side) and blocks of " +
          std::to_string(k_block_cells) +
          " cells; the share of all blocks, least–most over the frames.\n\n"
          "| path | frames | store tiles needed | " +
          std::to_string(k_block_cells) + "-cell blocks needed |\n|---|---|---|---|\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
        const Summary &s = sums[i];
        if (s.rebuilds == 0)
            continue;
        md += "| " + results[i].name + " | " + std::to_string(s.rebuilds) + " | " +
              fmt("%.0f", 100 * s.tiles_min) + "–" + fmt("%.0f %%", 100 * s.tiles_max) + " | " +
              fmt("%.0f", 100 * s.blocks_min) + "–" + fmt("%.0f %%", 100 * s.blocks_max) + " |\n";
    }
    md += "\nThen each path at " + fmt("%.0f", k_fps_interactive) +
          " frames per second of path time, as an interactive viewer samples them (the camera "
          "moves " +
          fmt("%.1f", k_fps_interactive / k_fps) +
          " times less per frame), by a new refiner built at the path's first view: each flight "
          "is the refiner's first over its path. The screen error is measured exhaustively over "
          "every DEM sample on every " +
          std::to_string(k_check_every) + "th frame (frames 1, " +
          std::to_string(k_check_every + 1) +
          ", ...).\n\n"
          "| path | updates | update CPU ms p50 / p99 / max | changed per frame median (max) | "
          "fixed ms + µs per changed node | r(time, changed) | r(time, nodes) | frames measured | "
          "max px |\n"
          "|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < flight.interactive.size(); ++i) {
        const Summary &s = isums[i];
        const PathResult &p = flight.interactive[i];
        md += "| " + p.name + " | " + std::to_string(p.rows.size()) + " of " +
              std::to_string(p.planned) + " | " + fmt("%.2f", s.p50) + " / " + fmt("%.2f", s.p99) +
              " / " + fmt("%.2f", s.max) + " | " + fmt("%.0f", s.changed_median) + " (" +
              fmt("%.0f", s.changed_max) + ") | " + fmt("%.1f", s.fixed_ms) + " + " +
              fmt("%.2f", s.us_per_changed) + " | " + fmt("%.2f", s.r_changed) + " (" +
              fmt("%.2f", s.pr_changed) + ") | " + fmt("%.2f", s.r_nodes) + " (" +
              fmt("%.2f", s.pr_nodes) + ") | " + std::to_string(s.checks) + " | " +
              fmt("%.3f", s.max_px) + " |\n";
    }
    md += "\nEach path flown a second time, right after its first flight, by the refiner that "
          "flew it (the jump back to its start not counted). *Undone*: the share of the "
          "recoveries that the update which made them erased again (the erases a deeper node's "
          "recovery had to bring back first).\n\n"
          "| path | flight | update CPU ms p50 / p99 / max | changed per frame median (max) | "
          "undone |\n|---|---|---|---|---|\n";
    const auto undone = [](const PathResult &p) {
        double recovered = 0, reerased = 0;
        for (const FrameRow &r : p.rows) {
            recovered += double(r.stats.update.recovered);
            reerased += double(r.stats.update.reerased);
        }
        return fmt("%.0f %%", 100 * reerased / std::max(1.0, recovered));
    };
    for (std::size_t i = 0; i < flight.repeated.size(); ++i)
        for (const PathResult *p : {&flight.interactive[i], &flight.repeated[i]}) {
            const Summary s = summarise(p->rows);
            md += "| " + p->name + " | " + (p == &flight.interactive[i] ? "first" : "second") +
                  " | " + fmt("%.2f", s.p50) + " / " + fmt("%.2f", s.p99) + " / " +
                  fmt("%.2f", s.max) + " | " + fmt("%.0f", s.changed_median) + " (" +
                  fmt("%.0f", s.changed_max) + ") | " + undone(*p) + " |\n";
        }
    md += "\nAnd at " + fmt("%.0f", k_fps_interactive) +
          " frames per second with the camera slower than the paths (the views of a higher "
          "frame rate of path time), each path from its start to its end by a new refiner: how "
          "fast an observer "
          "the refiner follows within the frame budget. Eye speed = the eye's path length over "
          "the time it takes. The screen error is measured at the same path times as above.\n\n"
          "| path | camera speed | eye speed m/s | updates | update CPU ms p50 / p99 / max | "
          "changed per frame median (max) | frames measured | max px |\n"
          "|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < flight.interactive.size(); ++i)
        for (std::size_t k = 0; k < ssums.size(); ++k) {
            const int slower = slower_of(k);
            const PathResult &p = k == 0 ? flight.interactive[i] : flight.slowed[k - 1][i];
            const Summary &s = ssums[k][i];
            md += "| " + p.name + " | " + speed_name(slower) + " | " +
                  fmt("%.0f", flight.eye_speed[i] / slower) + " | " +
                  std::to_string(p.rows.size()) + " of " + std::to_string(p.planned) + " | " +
                  fmt("%.2f", s.p50) + " / " + fmt("%.2f", s.p99) + " / " + fmt("%.2f", s.max) +
                  " | " + fmt("%.0f", s.changed_median) + " (" + fmt("%.0f", s.changed_max) +
                  ") | " + std::to_string(s.checks) + " | " + fmt("%.3f", s.max_px) + " |\n";
        }
    return md;
}

// The eye's mean speed along path p, m/s.
double eye_speed(const CameraPath &path) {
    const std::vector<View> views = path.sample(1001, View{});
    double length = 0.0;
    for (std::size_t i = 1; i < views.size(); ++i)
        length += glm::length(views[i].eye - views[i - 1].eye);
    return length / std::max(1e-9, path.duration());
}

FlyOptions parse(int argc, char **argv) {
    FlyOptions o;
    CLI::App app{"bench_fly: the flight benchmark (a Refiner over the ~4k² terrain, three paths)"};
    app.add_option("--data", o.data, "the shared data folder (dem/N42E001.hgt)")->required();
    app.add_option("--out", o.out, "results folder (flight.csv)")->required();
    app.add_option("--tmp", o.tmp, "scratch folder (plot series, flight.json)")->required();
    app.add_flag("--quick", o.quick, "2049² terrain, the first frames of each path");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        std::exit(app.exit(e));
    }
    return o;
}

void run(const FlyOptions &options) {
    Stopwatch total;
    // The suite's ~4k² terrain (enlarged_4097 in bench_suite's scaling); the quick run's 2049².
    const int side = options.quick ? 2049 : 4097;
    const Heightfield n42 = load_heightfield(options.data + "/dem/N42E001.hgt");
    const Heightfield hf = bench::enlarge(n42, double(side - 1) / (n42.width - 1));
    const QuadTree tree(hf);
    const std::string terrain = "enlarged_" + std::to_string(side) + " (" + std::to_string(side) +
                                "², N42E001 enlarged by bench::enlarge)";
    std::printf("== flight on %s, made in %.1f s\n", terrain.c_str(), total.ms() / 1e3);

    Flight flight;
    flight.samples = hf.size();
    std::unique_ptr<Refiner> refiner;
    const std::vector<FlightPath> paths = flight_paths(hf);
    for (const FlightPath &p : paths)
        flight.paths.push_back(fly(hf, tree, p, options.quick, k_fps, true, refiner, flight));
    std::printf("  at %.0f frames per second, each path by a new refiner, then again by it:\n",
                k_fps_interactive);
    for (const FlightPath &p : paths) {
        refiner.reset();
        flight.interactive.push_back(
            fly(hf, tree, p, options.quick, k_fps_interactive, false, refiner, flight));
        flight.repeated.push_back(
            fly(hf, tree, p, options.quick, k_fps_interactive, false, refiner, flight));
    }
    for (const int slower : k_slower) {
        std::printf("  at %.0f frames per second, the camera %d times slower:\n", k_fps_interactive,
                    slower);
        flight.slowed.emplace_back();
        for (const FlightPath &p : paths) {
            refiner.reset();
            flight.slowed.back().push_back(
                fly(hf, tree, p, options.quick, k_fps_interactive, false, refiner, flight, slower));
        }
    }
    for (const FlightPath &p : paths)
        flight.eye_speed.push_back(eye_speed(p.path));
    refiner.reset();
    const std::vector<PathResult> &results = flight.paths;

    std::vector<Summary> sums;
    std::vector<FrameRow> all;
    for (const PathResult &p : results) {
        sums.push_back(summarise(p.rows));
        all.insert(all.end(), p.rows.begin(), p.rows.end());
        const Summary &s = sums.back();
        std::printf("  %-8s p50 %.2f ms, p99 %.2f ms (CPU); r(time, changed) %.2f, r(time, "
                    "nodes) %.2f; %.0f B/node; rebuild ratio median %.0fx (lowest %.0fx); max px "
                    "flight %.3f, rebuild %.3f; heights needed: tiles %.0f-%.0f %%, blocks "
                    "%.0f-%.0f %%\n",
                    p.name.c_str(), s.p50, s.p99, s.r_changed, s.r_nodes, s.bytes_per_node,
                    s.ratio_median, s.ratio_min, s.max_px, s.rebuild_max_px, 100 * s.tiles_min,
                    100 * s.tiles_max, 100 * s.blocks_min, 100 * s.blocks_max);
    }
    const Summary pooled = summarise(all);
    std::vector<Summary> isums;
    for (const PathResult &p : flight.interactive) {
        isums.push_back(summarise(p.rows));
        const Summary &s = isums.back();
        std::printf("  %-8s at %.0f fps: p50 %.2f ms, p99 %.2f ms (CPU); max px %.3f on %d "
                    "frames\n",
                    p.name.c_str(), k_fps_interactive, s.p50, s.p99, s.max_px, s.checks);
    }
    std::vector<std::vector<Summary>> ssums{isums};
    for (std::size_t k = 0; k < flight.slowed.size(); ++k) {
        ssums.emplace_back();
        for (const PathResult &p : flight.slowed[k]) {
            ssums.back().push_back(summarise(p.rows));
            const Summary &s = ssums.back().back();
            std::printf("  %-8s at %.0f fps, %s speed: p50 %.2f ms, p99 %.2f ms (CPU); max px "
                        "%.3f on %d frames\n",
                        p.name.c_str(), k_fps_interactive, speed_name(k_slower[k]).c_str(), s.p50,
                        s.p99, s.max_px, s.checks);
        }
    }

    write_csv(options.out + "/flight.csv", flight);
    write_series(options.tmp + "/flight.dat", results);
    json doc;
    doc["claims"] = json::array();
    for (const Claim &c : claims(flight, sums, pooled, isums, ssums))
        doc["claims"].push_back(
            {{"claim", c.claim}, {"measured", c.measured}, {"verdict", c.verdict}});
    doc["section"] = section(flight, sums, pooled, isums, ssums, terrain, options.quick);
    doc["seconds"] = total.ms() / 1e3;
    doc["budget_s"] = options.quick ? k_quick_budget_s : k_budget_s;
    std::ofstream(options.tmp + "/flight.json") << doc.dump(1);
    std::printf("== flight: %.0f s\n", total.ms() / 1e3);
}

} // namespace

int main(int argc, char **argv) {
    try {
        run(parse(argc, argv));
    } catch (const std::exception &e) {
        std::fprintf(stderr, "bench_fly: %s\n", e.what());
        return 1;
    }
    return 0;
}
