// `tinlod simplify DEM --max-error M` against hmm (github fogleman/hmm: Garland-Heckbert greedy
// insertion in C++, vendored in peers/hmm and built beside this program) as users run both: whole
// processes (spawned, one core, least of alternated runs), on the same 16-bit grey PNG of each
// DEM, at the same vertical bound; delatin and martini (npm) on the same samples for their
// triangle counts. Every output is read back and measured over every sample (tinlod::measure_error
// against the PNG's heights), not taken from the program's own report.
//
// The PNG: v = (z - z_min) / step, with step = 2^-k the finest power of two that keeps the range
// within 16 bits, so a DEM whose heights are multiples of step (every integer DEM) is the PNG's
// exactly, and any other is within step / 2 (the inputs table says which). tinlod reads it with
// `--cell 1 --zscale step`; hmm scales a pixel by zscale / 65535 (src/heightmap.cpp: v / 65535,
// then src/triangulator.cpp: times -z) and takes -e in those normalised units, so it runs with
// `-z 65535*step -e M/(65535*step)`. Both write binary STL over the same grid (x = column,
// y = row from the south), which is read back as grid sample ids.
//
// Writes OUT/hmm.csv (one row per input x bound x contender) and OUT/hmm.md (the section run.sh
// appends to RESULTS.md, and docs/performance.md quotes).
//
// usage: bench_heightmap --bin DIR --meshes DIR --peers DIR --out DIR --tmp DIR [--quick]
//                        [--core N] [--command TEXT]
#include "tinlod/metrics.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/tin.hpp"
#include "tinlod/util.hpp"

#include "common.hpp"

#include <CLI/CLI.hpp>
#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace {

using namespace tinlod;
using bench::cell;
using bench::fmt;
using json = nlohmann::json;

struct Options {
    std::string bin;    // tinlod and hmm
    std::string meshes; // the repository's meshes/
    std::string peers;  // bench/peers (run_peers.mjs, node_modules)
    std::string out;    // bench/results
    std::string tmp;    // scratch: the PNGs, grids and outputs
    std::string command = "make bench";
    int core = 0; // every timed process runs on this core alone
    bool quick = false;
};

struct Input {
    std::string name, source;
    Heightfield hf;         // the PNG's heights, as tinlod loads them (--cell 1 --zscale step)
    std::string png, grid;  // the 16-bit PNG both programs read; float32 grid for the npm peers
    double step = 1.0;      // metres per PNG unit
    double offset = 0.0;    // the DEM's height of PNG value 0
    double png_error = 0.0; // max |PNG height - DEM height| over the samples, m
    std::vector<double> bounds;
};

std::string number(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

// Writes `dem` as a 16-bit grey PNG (row 0 north, as files run) in the finest power-of-two step
// its range allows, then loads it back as tinlod's CLI will; sets the input's step, offset and
// png_error.
void make_png(Input &in, const Heightfield &dem) {
    const double lo = dem.min_z(), range = double(dem.max_z()) - lo;
    in.step = range > 0 ? std::ldexp(1.0, -int(std::floor(std::log2(65535.0 / range)))) : 1.0;
    in.offset = lo;
    std::vector<std::uint16_t> pixels(dem.z.size());
    in.png_error = 0.0;
    for (int r = 0; r < dem.height; ++r)
        for (int c = 0; c < dem.width; ++c) {
            const double v = std::clamp(std::round((dem.at(c, r) - lo) / in.step), 0.0, 65535.0);
            pixels[std::size_t(dem.height - 1 - r) * dem.width + c] = std::uint16_t(v);
            in.png_error = std::max(in.png_error, std::abs(v * in.step + lo - dem.at(c, r)));
        }
    auto out = OIIO::ImageOutput::create(in.png);
    const OIIO::ImageSpec spec(dem.width, dem.height, 1, OIIO::TypeDesc::UINT16);
    if (!out || !out->open(in.png, spec) ||
        !out->write_image(OIIO::TypeDesc::UINT16, pixels.data()) || !out->close())
        throw std::runtime_error(in.png + ": cannot write the PNG");
    LoadOptions lo_options;
    lo_options.cell = 1.0;
    lo_options.zscale = in.step;
    in.hf = load_heightfield(in.png, lo_options);
    if (in.hf.width != dem.width || in.hf.height != dem.height)
        throw std::runtime_error(in.png + ": reads back at another size");
    for (int r = 0; r < dem.height; ++r)
        for (int c = 0; c < dem.width; ++c)
            if (in.hf.at(c, r) != pixels[std::size_t(dem.height - 1 - r) * dem.width + c] * in.step)
                throw std::runtime_error(in.png + ": reads back other heights than written");
}

// The triangles of a binary STL written over the grid of `hf` (x = column, y = row from the south,
// as both programs write a --cell 1 grid) as sample ids, counter-clockwise; *dz receives the
// largest |z - the sample's height| of its corners (hmm writes the PNG's heights, tinlod moves
// interior nodes within the bound: decisions/034), `heights` each node's written z by sample id.
std::vector<std::uint32_t> read_stl(const std::string &path, const Heightfield &hf, double *dz,
                                    std::vector<float> &heights) {
    std::ifstream in(path, std::ios::binary);
    char header[84];
    if (!in.read(header, sizeof header))
        throw std::runtime_error(path + ": not a binary STL");
    std::uint32_t n = 0;
    std::memcpy(&n, header + 80, 4);
    std::vector<char> body(std::size_t(n) * 50);
    if (!in.read(body.data(), std::streamsize(body.size())))
        throw std::runtime_error(path + ": truncated STL");
    std::vector<std::uint32_t> ids(std::size_t(n) * 3);
    *dz = 0.0;
    heights.assign(std::size_t(hf.size()), NAN);
    for (std::size_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k) {
            float p[3];
            std::memcpy(p, body.data() + t * 50 + 12 + k * 12, sizeof p);
            const long c = std::lround(p[0]), r = std::lround(p[1]);
            if (c < 0 || c >= hf.width || r < 0 || r >= hf.height || c != p[0] || r != p[1])
                throw std::runtime_error(path + ": a vertex off the grid");
            ids[t * 3 + k] = std::uint32_t(r * hf.width + c);
            heights[ids[t * 3 + k]] = p[2];
            *dz = std::max(*dz, std::abs(double(p[2]) - hf.at(int(c), int(r))));
        }
    bench::orient_ccw(hf, ids);
    return ids;
}

// The exhaustive measurement of a TIN over the grid, into row `r`: at its nodes' written heights
// when given (by sample id), else at their samples'.
void measure(json &r, const Heightfield &hf, const std::vector<std::uint32_t> &tris,
             const std::vector<float> *heights = nullptr) {
    TinError e;
    if (heights) {
        Mesh tin = tin_from_indices(hf, tris);
        const auto origin = find_origin_property(tin);
        for (const auto v : tin.vertices())
            tin.point(v)[2] = (*heights)[std::size_t(tin.property(origin, v))];
        e = measure_error(hf, tin);
    } else {
        e = measure_error(hf, tris);
    }
    r["tris"] = std::int64_t(tris.size() / 3);
    r["nodes"] = std::int64_t(std::set<std::uint32_t>(tris.begin(), tris.end()).size());
    r["max_vertical"] = e.max_vertical;
    r["rms_vertical"] = e.rms_vertical;
    r["uncovered"] = e.uncovered;
    r["folded"] = bench::folded_triangles(hf, tris);
}

struct Timed {
    std::vector<double> ms, cpu_ms;
    double peak_mb = 0.0; // from the warm-up run under /usr/bin/time
    json stats;           // tinlod's --stats of its fastest run
};

json timed_row(const std::string &contender, const Input &in, double bound, const Timed &t) {
    std::vector<double> ms = t.ms;
    std::sort(ms.begin(), ms.end());
    const auto fastest = std::min_element(t.ms.begin(), t.ms.end()) - t.ms.begin();
    return {{"input", in.name},
            {"bound", bound},
            {"contender", contender},
            {"reps", ms.size()},
            {"ms", ms.front()},
            {"ms_median", ms[(ms.size() - 1) / 2]},
            {"cpu_ms", t.cpu_ms[std::size_t(fastest)]},
            {"peak_rss_mb", t.peak_mb}};
}

struct Bench {
    Options options;
    std::vector<json> rows;
    json split; // the one case broken into stages

    std::string tinlod() const { return options.bin + "/tinlod"; }
    std::string hmm() const { return options.bin + "/hmm"; }
    int min_reps() const { return options.quick ? 3 : 5; }
    double extra_ms() const { return options.quick ? 4e3 : 15e3; }

    void run_or_throw(const std::vector<std::string> &argv, Timed &t, bool quiet = false) const {
        const bench::ProcessResult p = bench::run_process(argv, options.core, quiet);
        if (p.status != 0)
            throw std::runtime_error(argv[0] + " failed (status " + std::to_string(p.status) + ")");
        t.ms.push_back(p.wall_ms);
        t.cpu_ms.push_back(p.cpu_ms);
    }

    // An untimed warm-up run (the input and the program into the page cache) through
    // /usr/bin/time, for the peak memory of the process itself: /usr/bin/time forks it from its
    // own small process, where wait4 here would count this process's peak too.
    void warm_up(const std::vector<std::string> &argv, Timed &t) const {
        const std::string file = options.tmp + "/peak.txt";
        std::vector<std::string> timed = {"/usr/bin/time", "-f", "%M", "-o", file};
        timed.insert(timed.end(), argv.begin(), argv.end());
        const bench::ProcessResult p = bench::run_process(timed, options.core);
        std::ifstream in(file);
        double kb = 0.0;
        if (p.status != 0 || !(in >> kb))
            throw std::runtime_error(argv[0] + " failed (status " + std::to_string(p.status) + ")");
        t.peak_mb = kb / 1024.0;
    }

    // Both programs at `bound`: a warm-up run each, then alternated (which goes first alternates
    // too), each run just after its program's start-up alone (`tinlod --version`, `hmm -?`), timed
    // in the same conditions; then their outputs measured, and delatin's and (on a 2^k+1 square)
    // martini's. Runs: at least 3; up to min_reps() while the case has taken under 60 s; then
    // more, up to 15, while it has taken under extra_ms(): on the shared VM the least of many
    // short runs is what steadies the small inputs' times.
    void run_case(const Input &in, double bound) {
        const std::string t_out = options.tmp + "/tinlod.stl", h_out = options.tmp + "/hmm.stl",
                          t_stats = options.tmp + "/tinlod.json";
        const double z = 65535.0 * in.step;
        const std::vector<std::string> t_argv = {
            tinlod(),      "--threads", "1",        "simplify",      in.png,
            "--cell",      "1",         "--zscale", number(in.step), "--max-error",
            number(bound), "-o",        t_out,      "--stats",       t_stats};
        const std::vector<std::string> h_argv = {
            hmm(), in.png, h_out, "-z", number(z), "-e", number(bound / z), "-q"};
        std::printf("%-14s %5.1f m ", in.name.c_str(), bound);
        std::fflush(stdout);
        Timed t, h, t_start, h_start;
        warm_up(t_argv, t);
        warm_up(h_argv, h);
        auto run_tinlod = [&] {
            run_or_throw({tinlod(), "--version"}, t_start);
            run_or_throw(t_argv, t);
            if (t.ms.back() == *std::min_element(t.ms.begin(), t.ms.end())) {
                std::ifstream s(t_stats);
                t.stats = json::parse(s);
            }
        };
        auto run_hmm = [&] {
            run_or_throw({hmm(), "-?"}, h_start, true); // its help goes to stderr
            run_or_throw(h_argv, h);
        };
        Stopwatch clock;
        auto more = [&](int i) {
            return i < 3 || (i < min_reps() && clock.ms() < 60e3) ||
                   (i < 15 && clock.ms() < extra_ms());
        };
        for (int i = 0; more(i); ++i) {
            if (i % 2 == 0) {
                run_tinlod();
                run_hmm();
            } else {
                run_hmm();
                run_tinlod();
            }
        }
        json tr = timed_row("tinlod", in, bound, t), hr = timed_row("hmm", in, bound, h);
        double dz = 0.0;
        std::vector<float> heights;
        measure(tr, in.hf, read_stl(t_out, in.hf, &dz, heights), &heights);
        tr["z_mismatch"] = dz;
        // hmm at its samples' heights: it writes them through floats of its own scale (z_mismatch).
        measure(hr, in.hf, read_stl(h_out, in.hf, &dz, heights));
        hr["z_mismatch"] = dz;
        for (const auto &[stage, ms] : t.stats["time_ms"].items())
            tr["stage_" + stage] = ms;
        tr["first_stage"] = t.stats["retrieve"]["first_stage"];
        tr["startup_ms"] = *std::min_element(t_start.ms.begin(), t_start.ms.end());
        hr["startup_ms"] = *std::min_element(h_start.ms.begin(), h_start.ms.end());
        std::vector<json> peers;
        for (const std::string tool : {"delatin", "martini"}) {
            if (tool == "martini" &&
                (in.hf.width != in.hf.height || ((in.hf.width - 1) & (in.hf.width - 2)) != 0))
                continue;
            bench::NodePeerRun p =
                bench::run_node_peer(options.peers, in.grid, in.hf, options.tmp + "/" + tool, tool,
                                     "max_error", bound, 1);
            json r = {{"input", in.name},
                      {"bound", bound},
                      {"contender", tool},
                      {"reps", 1},
                      {"meshing_ms", p.report["ms"][0]}};
            measure(r, in.hf, p.tris);
            peers.push_back(r);
        }
        const double hmm_tris = hr["tris"], hmm_ms = hr["ms"];
        for (json *r : {&tr, &hr})
            (*r)["ms_x_hmm"] = (*r)["ms"].get<double>() / hmm_ms;
        tr["tris_x_hmm"] = tr["tris"].get<double>() / hmm_tris;
        hr["tris_x_hmm"] = 1.0;
        for (json &r : peers)
            r["tris_x_hmm"] = r["tris"].get<double>() / hmm_tris;
        std::printf("tinlod %7lld tris %8.1f ms | hmm %7lld tris %8.1f ms | %.3f× tris, %.2f× "
                    "time\n",
                    static_cast<long long>(tr["tris"].get<std::int64_t>()), tr["ms"].get<double>(),
                    static_cast<long long>(hr["tris"].get<std::int64_t>()), hmm_ms,
                    tr["tris_x_hmm"].get<double>(), tr["ms_x_hmm"].get<double>());
        rows.push_back(tr);
        rows.push_back(hr);
        for (json &r : peers)
            rows.push_back(r);
    }
};

const std::vector<std::string> k_columns = {
    "input",       "bound",          "contender",     "reps",           "ms",
    "ms_median",   "cpu_ms",         "ms_x_hmm",      "tris",           "tris_x_hmm",
    "nodes",       "max_vertical",   "rms_vertical",  "uncovered",      "folded",
    "z_mismatch",  "peak_rss_mb",    "meshing_ms",    "startup_ms",     "first_stage",
    "stage_load",  "stage_retrieve", "stage_convert", "stage_simplify", "stage_measure",
    "stage_write", "error"};

const json *find(const std::vector<json> &rows, const std::string &input, double bound,
                 const std::string &contender) {
    for (const json &r : rows)
        if (r["input"] == input && r["bound"] == bound && r["contender"] == contender)
            return &r;
    return nullptr;
}

std::string ratio(const json *r, const char *key) {
    return r ? fmt("%.3f", (*r)[key].get<double>()) : "–";
}

void write_markdown(const Bench &b, const std::vector<Input> &inputs, double seconds) {
    std::ofstream md(b.options.out + "/hmm.md");
    const std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    md << "\n## Against hmm (greedy insertion) (bench_heightmap; hmm.csv)"
       << (b.options.quick ? " — QUICK run" : "") << "\n\n"
       << date << ", `" << b.options.command
       << "`. Whole processes as users run them, each pinned to core " << b.options.core
       << ": `tinlod --threads 1 simplify DEM.png --cell 1 --zscale STEP --max-error M -o "
          "OUT.stl --stats S.json` against `hmm DEM.png OUT.stl -z 65535·STEP -e M/(65535·STEP) "
          "-q` (github fogleman/hmm, vendored in bench/peers/hmm, built with our Release flags), "
          "on the same 16-bit PNG, so both see the same samples and the same xy metric; "
          "alternated runs, the least wall time of 3 to 15 each (spawn to exit, after an "
          "untimed warm-up run each; 3 on the slowest cases, "
       << b.min_reps() << " or more on the others, more while the case has taken under "
       << fmt("%.0f", b.extra_ms() / 1e3)
       << " s), and the CPU time (user + system) of those fastest runs. Triangles and L∞ are "
          "measured: "
          "each output read back and compared with every sample (`measure_error`). delatin and "
          "martini (npm, in Node; martini on 2^k+1 squares only) run once on the same samples at "
          "the same bound, for their triangle counts. Ratios are tinlod ÷ hmm (triangles, time) "
          "and peer ÷ hmm (triangles).\n\n"
       << "| input | M m | tinlod tris | hmm tris | tinlod ÷ hmm tris | delatin ÷ hmm | martini "
          "÷ hmm | L∞ tinlod | L∞ hmm | L∞ delatin | tinlod ms | hmm ms | tinlod ÷ hmm time | "
          "tinlod ÷ hmm CPU | tinlod ÷ hmm time, start-ups taken off |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    int cases = 0, tris_met = 0, time_met = 0, cpu_met = 0, t_bounded = 0, h_bounded = 0;
    double tris_lo = 1e30, tris_hi = 0, time_lo = 1e30, time_hi = 0, start_lo = 1e30, start_hi = 0,
           hmm_start_hi = 0, cpu_lo = 1e30, cpu_hi = 0;
    for (const Input &in : inputs)
        for (double bound : in.bounds) {
            const json *t = find(b.rows, in.name, bound, "tinlod"),
                       *h = find(b.rows, in.name, bound, "hmm"),
                       *d = find(b.rows, in.name, bound, "delatin"),
                       *m = find(b.rows, in.name, bound, "martini");
            if (!t || !h) {
                const json *e = find(b.rows, in.name, bound, "case");
                md << "| " << in.name << " | " << number(bound)
                   << " | failed: " << (e ? cell(*e, "error") : "") << " |||||||||||||\n";
                continue;
            }
            const double xt = (*t)["tris_x_hmm"], xs = (*t)["ms_x_hmm"],
                         xc = (*t)["cpu_ms"].get<double>() / (*h)["cpu_ms"].get<double>();
            ++cases;
            tris_met += xt <= 0.85;
            time_met += xs <= 1.0;
            cpu_met += xc <= 1.0;
            cpu_lo = std::min(cpu_lo, xc);
            cpu_hi = std::max(cpu_hi, xc);
            tris_lo = std::min(tris_lo, xt);
            tris_hi = std::max(tris_hi, xt);
            time_lo = std::min(time_lo, xs);
            time_hi = std::max(time_hi, xs);
            start_lo = std::min(start_lo, (*t)["startup_ms"].get<double>());
            start_hi = std::max(start_hi, (*t)["startup_ms"].get<double>());
            hmm_start_hi = std::max(hmm_start_hi, (*h)["startup_ms"].get<double>());
            t_bounded += (*t)["max_vertical"].get<double>() <= bound;
            h_bounded += (*h)["max_vertical"].get<double>() <= bound;
            md << "| " << in.name << " | " << number(bound) << " | " << cell(*t, "tris") << " | "
               << cell(*h, "tris") << " | " << fmt("%.3f", xt) << " | " << ratio(d, "tris_x_hmm")
               << " | " << ratio(m, "tris_x_hmm") << " | " << fmt("%.3f", (*t)["max_vertical"])
               << " | " << fmt("%.3f", (*h)["max_vertical"]) << " | "
               << (d ? fmt("%.3f", (*d)["max_vertical"]) : "–") << " | " << fmt("%.0f", (*t)["ms"])
               << " | " << fmt("%.0f", (*h)["ms"]) << " | " << fmt("%.2f", xs) << " | "
               << fmt("%.2f", xc) << " | "
               << fmt("%.2f", ((*t)["ms"].get<double>() - (*t)["startup_ms"].get<double>()) /
                                  ((*h)["ms"].get<double>() - (*h)["startup_ms"].get<double>()))
               << " |\n";
        }
    if (cases > 0)
        md << "\nGoals (issue #50): tinlod ≤ 0.85× hmm's triangles in " << tris_met << " of "
           << cases << " cases (tinlod ÷ hmm " << fmt("%.3f", tris_lo) << "–"
           << fmt("%.3f", tris_hi) << "); whole process ≤ 1.0× hmm's time in " << time_met << " of "
           << cases << " (" << fmt("%.2f", time_lo) << "–" << fmt("%.2f", time_hi)
           << "×; by CPU time in " << cpu_met << ", " << fmt("%.2f", cpu_lo) << "–"
           << fmt("%.2f", cpu_hi) << "×). Measured L∞ ≤ M: tinlod in " << t_bounded << ", hmm in "
           << h_bounded << " of " << cases
           << ". Start-up alone (least per case, run beside each): `tinlod --version` "
           << fmt("%.0f", start_lo) << "–" << fmt("%.0f", start_hi) << " ms, `hmm -?` ≤ "
           << fmt("%.1f", hmm_start_hi) << " ms.\n";
    md << "\n| input | size | PNG step m | PNG = DEM? | source |\n|---|---|---|---|---|\n";
    for (const Input &in : inputs)
        md << "| " << in.name << " | " << in.hf.width << "×" << in.hf.height << " | "
           << number(in.step) << " | "
           << (in.png_error == 0 ? std::string("exactly")
                                 : "within " + fmt("%.4f", in.png_error) +
                                       " m (measured against "
                                       "the PNG)")
           << " | " << in.source << " |\n";
    if (!b.split.is_null()) {
        const json &s = b.split;
        const double wall = s["ms"];
        double staged = 0.0;
        md << "\n**Where tinlod's whole process goes** (" << cell(s, "input") << ", "
           << cell(s, "bound")
           << " m; the fastest run's wall time and its `--stats` `time_ms`; start-up = `tinlod "
              "--version`)\n\n"
              "| part | ms | share |\n|---|---|---|\n";
        auto line = [&](const std::string &part, double ms) {
            md << "| " << part << " | " << fmt("%.1f", ms) << " | "
               << fmt("%.0f %%", 100.0 * ms / wall) << " |\n";
        };
        line("start-up (`tinlod --version`, least of its runs beside this case's)",
             s["startup_ms"]);
        const std::vector<std::pair<std::string, std::string>> stages = {
            {"stage_load", "load"},
            {"stage_retrieve", std::string("first stage (") + cell(s, "first_stage") + ")"},
            {"stage_convert", "convert"},
            {"stage_simplify", "erase"},
            {"stage_measure", "measure (exhaustive L∞)"},
            {"stage_write", "write"}};
        for (const auto &[key, part] : stages)
            if (s.contains(key)) {
                line(part, s[key]);
                staged += s[key].get<double>();
            }
        line("the rest (in no stage: options, exit, ...)",
             wall - s["startup_ms"].get<double>() - staged);
        line("whole process", wall);
        md << "\nPeak resident memory (`/usr/bin/time -f %M`, the warm-up run): tinlod "
           << fmt("%.0f", s["peak_rss_mb"]) << " MB, hmm "
           << fmt("%.0f", (*find(b.rows, s["input"], s["bound"], "hmm"))["peak_rss_mb"])
           << " MB. tinlod's CPU time in its fastest run: " << fmt("%.0f", s["cpu_ms"]) << " ms.\n";
    }
    md << "\nSection time: " << fmt("%.0f", seconds) << " s.\n";
}

Options parse(int argc, char **argv) {
    Options o;
    CLI::App app{"bench_heightmap: tinlod simplify --max-error against hmm, whole processes"};
    app.add_option("--bin", o.bin, "the folder holding tinlod and hmm")->required();
    app.add_option("--meshes", o.meshes, "the repository's meshes/")->required();
    app.add_option("--peers", o.peers, "bench/peers (run_peers.mjs, node_modules)")->required();
    app.add_option("--out", o.out, "results folder (hmm.csv, hmm.md)")->required();
    app.add_option("--tmp", o.tmp, "scratch folder")->required();
    app.add_option("--core", o.core, "the core every timed process runs on")->capture_default_str();
    app.add_option("--command", o.command, "the command the section names")->capture_default_str();
    app.add_flag("--quick", o.quick, "the quick run: fewer inputs, bounds and repetitions");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        std::exit(app.exit(e));
    }
    return o;
}

void run(const Options &options) {
    bench::require_node_peers(options.peers);
    Stopwatch section;
    Bench b;
    b.options = options;
    std::filesystem::create_directories(options.tmp); // the PNGs and outputs are written there
    std::filesystem::create_directories(options.out);
    const std::vector<double> all = {0.5, 1, 2, 5, 10, 20};
    const std::vector<double> few = {1, 5, 20};
    std::vector<Input> inputs;
    auto add = [&](std::string name, std::string source, const Heightfield &dem,
                   const std::vector<double> &bounds) {
        Input &in = inputs.emplace_back();
        in.name = std::move(name);
        in.source = std::move(source);
        in.png = options.tmp + "/" + in.name + ".png";
        in.grid = options.tmp + "/" + in.name + ".f32";
        in.bounds = bounds;
        make_png(in, dem);
        bench::write_grid_f32(in.hf, in.grid);
        std::printf("input %s: %dx%d, step %g m, PNG within %g m of the DEM\n", in.name.c_str(),
                    in.hf.width, in.hf.height, in.step, in.png_error);
    };
    const std::string m = options.meshes + "/";
    const Heightfield n42 = load_heightfield(m + "N42E001.hgt");
    if (!options.quick)
        add("N42E001", "meshes/N42E001.hgt (SRTM3, voids filled by the loader)", n42, all);
    add("N42E001_1025", "1025² crop (SW corner) of meshes/N42E001.hgt",
        bench::crop(n42, 1025, 1025), options.quick ? std::vector<double>{5} : all);
    add("dem_srtm30", "meshes/dem_srtm30.tif (SRTM30)", load_heightfield(m + "dem_srtm30.tif"),
        options.quick ? few : all);
    if (!options.quick)
        add("dem_squared", "meshes/dem_squared.tif (USGS NED, float32)",
            load_heightfield(m + "dem_squared.tif"), all);
    add("crater_u16", "meshes/crater_u16.png (16-bit PNG)", load_heightfield(m + "crater_u16.png"),
        options.quick ? few : all);

    for (const Input &in : inputs)
        for (double bound : in.bounds)
            try {
                b.run_case(in, bound);
            } catch (const std::exception &e) {
                std::printf("FAILED: %s\n", e.what());
                b.rows.push_back({{"input", in.name},
                                  {"bound", bound},
                                  {"contender", "case"},
                                  {"error", e.what()}});
            }
    if (const json *s = find(b.rows, "crater_u16", 5.0, "tinlod"))
        b.split = *s;
    bench::write_csv(options.out + "/hmm.csv", k_columns, b.rows);
    write_markdown(b, inputs, section.ms() / 1e3);
    std::printf("== hmm: %.0f s; results in %s/hmm.csv, hmm.md\n", section.ms() / 1e3,
                options.out.c_str());
}

} // namespace

int main(int argc, char **argv) {
    try {
        run(parse(argc, argv));
    } catch (const std::exception &e) {
        std::fprintf(stderr, "bench_heightmap: %s\n", e.what());
        return 1;
    }
    return 0;
}
