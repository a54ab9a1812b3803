// `tinlod`: view-dependent TINs from elevation rasters and meshes (see README.md).
#include "commands.hpp"

#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"
#include "tinlod/store.hpp"
#include "tinlod/util.hpp"
#include "tinlod/version.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <filesystem>
#include <limits>
#include <string>

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

namespace tinlod::cli {

std::vector<Command> &registry() {
    static std::vector<Command> commands;
    return commands;
}

// The process's age, ms: the kernel's record of its start (clock ticks since boot, 10 ms apart)
// against the boot clock; 0 where /proc cannot tell.
static double process_age_ms() {
    std::FILE *f = std::fopen("/proc/self/stat", "r");
    if (!f)
        return 0.0;
    char line[1024];
    const bool read = std::fgets(line, sizeof line, f) != nullptr;
    std::fclose(f);
    const char *fields = read ? std::strrchr(line, ')') : nullptr; // the name may hold spaces
    unsigned long long start_ticks = 0;
    // Field 22, starttime, is the 20th after the name.
    if (!fields || std::sscanf(fields + 1,
                               "%*s %*s %*s %*s %*s %*s %*s %*s %*s %*s %*s %*s %*s "
                               "%*s %*s %*s %*s %*s %*s %llu",
                               &start_ticks) != 1)
        return 0.0;
    timespec now{};
    clock_gettime(CLOCK_BOOTTIME, &now);
    const double age = (double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6) -
                       double(start_ticks) * 1e3 / double(sysconf(_SC_CLK_TCK));
    return std::max(age, 0.0);
}

StageTimes::StageTimes() : started_ms_(process_age_ms()) {
    stages_.emplace_back("start", started_ms_);
    laps_ms_ = started_ms_;
}

double StageTimes::lap(const std::string &name) {
    const double ms = clock_.ms();
    clock_.reset();
    stages_.emplace_back(name, std::max(ms - added_ms_, 0.0));
    laps_ms_ += ms;
    added_ms_ = 0.0;
    return stages_.back().second;
}

void StageTimes::add(const std::string &name, double ms) {
    stages_.emplace_back(name, ms);
    added_ms_ += ms;
}

void StageTimes::rename(const std::string &from, const std::string &to) {
    for (auto &stage : stages_)
        if (stage.first == from)
            stage.first = to;
}

double StageTimes::total() const { return laps_ms_; }

nlohmann::json StageTimes::json() const {
    nlohmann::json j = nlohmann::json::object();
    for (const auto &[name, ms] : stages_)
        j[name] = ms;
    j["total"] = total();
    return j;
}

std::string StageTimes::summary() const {
    char part[96];
    std::snprintf(part, sizeof part, "%.0f ms (", total());
    std::string text = part;
    for (std::size_t i = 0; i < stages_.size(); ++i) {
        std::snprintf(part, sizeof part, "%s%s %.0f", i > 0 ? ", " : "", stages_[i].first.c_str(),
                      stages_[i].second);
        text += part;
    }
    return text + ")";
}

// --threads N: a whole number from 1 to 1024, or 0 when the text is not one.
static int parse_threads(const std::string &text) {
    if (text.empty() || text.size() > 4 ||
        !std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); }))
        return 0;
    const int n = std::stoi(text);
    return n <= 1024 ? n : 0;
}

static void apply_threads(int n) {
    set_max_threads(n);
    // Mesa's software rasteriser (render, compare) sizes its own pool from this variable.
    ::setenv("LP_NUM_THREADS", std::to_string(n).c_str(), 1);
}

// The heap, set for one run over large arrays (docs/decisions/024-simplify-speed.md). By default
// glibc maps each block over 128 KiB on its own, unmaps it when freed and trims the heap's top, so
// each next array faults its pages in again, 4 KiB at a time: on a VM a few microseconds each, a
// third of `simplify`'s CPU time on a small DEM. Here blocks up to glibc's largest threshold
// (32 MiB; larger ones are still mapped apart, and their memory goes back when freed) come from
// the heap, a freed one stays there for the next, and the heap reserves its first GiB at once,
// advised for 2 MiB pages (one fault where there were 512). Address space only: a page costs
// memory once written.
static void tune_heap() {
    constexpr int reserve = 1 << 30;
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
    mallopt(M_TOP_PAD, reserve);
    char *const before = static_cast<char *>(sbrk(0));
    void *const probe = std::malloc(std::size_t(1) << 20); // more than the heap's top holds
    mallopt(M_TOP_PAD, 64 << 20);
    char *const after = static_cast<char *>(sbrk(0));
    std::free(probe);
    constexpr std::uintptr_t huge = std::uintptr_t(2) << 20;
    const std::uintptr_t lo = (reinterpret_cast<std::uintptr_t>(before) + huge - 1) & ~(huge - 1);
    const std::uintptr_t hi = reinterpret_cast<std::uintptr_t>(after) & ~(huge - 1);
#ifdef MADV_HUGEPAGE
    if (probe && before != reinterpret_cast<char *>(-1) && hi > lo)
        madvise(reinterpret_cast<void *>(lo), hi - lo, MADV_HUGEPAGE);
#endif
}

} // namespace tinlod::cli

int main(int argc, char **argv) {
    tinlod::cli::tune_heap();
    // Past a file-size limit (ulimit -f) a write then fails with EFBIG ("File too large"), reported
    // as any failed write, its temporary removed, instead of SIGXFSZ killing the process silently.
    std::signal(SIGXFSZ, SIG_IGN);
    using namespace tinlod::cli;
    CLI::App app{
        "tinlod: view-dependent triangulated irregular networks from elevation rasters and "
        "meshes"};
    app.require_subcommand(1);
    app.set_version_flag("--version", tinlod::version_line("tinlod"));
    app.footer(
        "Exit status: 0 done; 1 bad input or failed work, 2 a usage error (a wrong option or "
        "value, found before any work); either prints one line on stderr, "
        "`tinlod: error: FILE or OPTION: problem`.");
    std::string threads;
    const CLI::Option *threads_option =
        app.add_option("--threads", threads,
                       "threads to run at once: loading, building, measuring, rendering (default: "
                       "every core)");
    // Options of the main command may also follow the subcommand's.
    app.fallthrough();
    auto &commands = registry();
    std::sort(commands.begin(), commands.end(),
              [](const Command &a, const Command &b) { return a.order < b.order; });
    std::vector<std::pair<CLI::App *, std::function<void()>>> runs;
    for (auto &c : commands) {
        CLI::App *sub = nullptr;
        runs.emplace_back(nullptr, nullptr);
        runs.back().second = c.setup(*(sub = app.add_subcommand(c.name, "")));
        runs.back().first = sub;
    }
    // Exit status: 0 done (--help and --version print to stdout), 1 bad input or failed work,
    // 2 a usage error; every error is one line on stderr, `tinlod: error: ...`.
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp &e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp &e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion &e) {
        return app.exit(e);
    } catch (const CLI::ParseError &e) {
        std::string help = "tinlod";
        for (const auto &[sub, run] : runs)
            if (sub->parsed())
                help += " " + sub->get_name();
        std::fprintf(stderr, "tinlod: error: %s (see `%s --help`)\n", e.what(), help.c_str());
        return 2;
    }
    if (threads_option->count() > 0) {
        const int n = parse_threads(threads);
        if (n == 0) {
            std::fprintf(
                stderr,
                "tinlod: error: --threads: must be a whole number from 1 to 1024, not '%s'\n",
                threads.c_str());
            return 2; // a usage error, found before any work
        }
        apply_threads(n);
    }
    tinlod::install_interrupt_handlers();
    try {
        for (auto &[sub, run] : runs)
            if (sub->parsed())
                run();
    } catch (const tinlod::Interrupted &e) {
        std::fprintf(stderr, "tinlod: interrupted\n");
        return 128 + e.signal();
    } catch (const UsageError &e) {
        std::fprintf(stderr, "tinlod: error: %s\n", e.what());
        return 2;
    } catch (const tinlod::Error &e) {
        std::fprintf(stderr, "tinlod: error: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "tinlod: error: out of memory\n");
        return 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "tinlod: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
