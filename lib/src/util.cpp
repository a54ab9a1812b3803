// Atomic writes, timing, memory, progress, the thread count.
#include "tinlod/util.hpp"
#include "tinlod/error.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/types.h>
#include <unistd.h>

#ifndef MADV_COLLAPSE
#define MADV_COLLAPSE 25 // Linux 6.1: glibc 2.36's headers lack it; an older kernel refuses it
#endif

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

namespace tinlod {

namespace fs = std::filesystem;

static volatile std::sig_atomic_t g_interrupt = 0; // the signal that came, 0 for none
static std::atomic<int> g_deferrals{0};            // the Deferral objects alive

static_assert(std::atomic<int>::is_always_lock_free, "read in a signal handler");

// An interrupt signal ends the process at once (its default action) unless a Deferral lives: then
// it only sets the flag check_interrupt() reads, and a second one ends the process.
static void on_interrupt(int signal) {
    std::signal(signal, SIG_DFL);
    if (g_deferrals.load() > 0)
        g_interrupt = signal;
    else
        std::raise(signal);
}

void install_interrupt_handlers() {
    for (const int signal : {SIGINT, SIGTERM, SIGHUP})
        if (std::signal(signal, on_interrupt) == SIG_IGN)
            std::signal(signal, SIG_IGN); // ignored by who started us (nohup, a background job)
}

void check_interrupt() {
    if (const int signal = g_interrupt)
        throw Interrupted(signal);
}

Deferral::Deferral() { ++g_deferrals; }
Deferral::~Deferral() { --g_deferrals; }

static fs::path folder_of(const fs::path &target) {
    return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

// Throws Error naming `subject` when `folder` (called `what` in the message) is missing or not
// writable.
static void check_folder(const std::string &subject, const fs::path &folder,
                         const std::string &what) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        throw Error(subject, what + " does not exist");
    if (::access(folder.c_str(), W_OK) != 0)
        throw Error(subject, what + " is not writable");
}

// Whether `folder` is a process's folder of open file descriptors, /proc/PID/fd (/dev/fd and
// /proc/self/fd lead there): its entries are links to whatever each descriptor is open on.
static bool is_descriptor_folder(const fs::path &folder) {
    std::error_code ec;
    const fs::path real = fs::canonical(folder, ec);
    return !ec && real.filename() == "fd" && real.parent_path().parent_path() == "/proc";
}

// What an output path leads to: the file to replace (its symbolic links followed), or a stream to
// write directly.
struct Target {
    fs::path file;
    bool stream = false;
};

// What `-` names: the standard output, or the descriptor divert_standard_output() kept it on.
static std::string g_standard_output = "/dev/stdout";

void divert_standard_output() {
    std::fflush(stdout);
    const int fd = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 3);
    if (fd < 0)
        return;
    if (::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
        ::close(fd);
        return;
    }
    g_standard_output = "/dev/fd/" + std::to_string(fd);
}

static Target resolve_output(const std::string &path) {
    if (path == "-")
        return {g_standard_output, true};
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (fs::is_character_file(status) || fs::is_fifo(status))
        return {path, true};
    if (fs::is_block_file(status))
        throw Error(path, "output path is a block device");
    if (fs::is_socket(status))
        throw Error(path, "output path is a socket");
    // Followed link by link, not by fs::canonical: a dangling link names the file to create.
    fs::path file(path);
    for (int links = 0; fs::is_symlink(fs::symlink_status(file, ec)); ++links) {
        if (links == 40) // the kernel's own limit (ELOOP)
            throw Error(path, "too many levels of symbolic links");
        if (is_descriptor_folder(folder_of(file)))
            return {path, true}; // /dev/stdout redirected to a file: write where it points
        const fs::path link = fs::read_symlink(file, ec);
        if (ec)
            throw Error(path, "cannot read the symbolic link: " + ec.message());
        file = link.is_absolute() ? link : folder_of(file) / link;
    }
    return {file, false};
}

bool is_stream(const std::string &path) { return resolve_output(path).stream; }

bool same_output(const std::string &a, const std::string &b) {
    if (a.empty() || b.empty())
        return false;
    Target ta, tb;
    try {
        ta = resolve_output(a);
        tb = resolve_output(b);
    } catch (const Error &) {
        return false; // not an output at all, as check_writable will say
    }
    std::error_code ec;
    if (fs::exists(ta.file, ec) && fs::exists(tb.file, ec))
        return fs::equivalent(ta.file, tb.file, ec) && !fs::is_character_file(ta.file, ec);
    const auto normal = [](const fs::path &p) {
        std::error_code ec;
        const fs::path absolute = fs::absolute(p, ec);
        const fs::path real = fs::weakly_canonical(absolute, ec);
        return ec ? absolute.lexically_normal() : real;
    };
    return normal(ta.file) == normal(tb.file);
}

static void remove_stale_temporaries(const fs::path &folder);

// The checks of write_atomically on `path`; returns what it leads to.
static Target check_output(const std::string &path) {
    const Target target = resolve_output(path);
    if (target.stream) {
        if (::access(target.file.c_str(), W_OK) != 0)
            throw Error(path, std::string("cannot write: ") + std::strerror(errno));
        return target;
    }
    const fs::path folder = folder_of(target.file);
    check_folder(path, folder, "output folder '" + folder.string() + "'");
    std::error_code ec;
    if (fs::is_directory(target.file, ec))
        throw Error(path, "output path is a folder");
    return target;
}

void check_writable(const std::vector<std::string> &paths) {
    for (const std::string &path : paths) {
        if (path.empty())
            continue;
        const Target target = check_output(path);
        if (!target.stream)
            remove_stale_temporaries(folder_of(target.file));
    }
}

void check_writable_folder(const std::string &folder) {
    std::error_code ec;
    fs::path existing(folder);
    while (!fs::exists(existing, ec) && existing.has_relative_path() && existing.has_parent_path())
        existing = existing.parent_path();
    if (!fs::exists(existing, ec))
        existing = ".";
    if (!fs::is_directory(existing, ec))
        throw Error(folder, existing.string() == folder
                                ? "output folder is not a folder"
                                : "'" + existing.string() + "' is not a folder");
    if (::access(existing.c_str(), W_OK) != 0)
        throw Error(folder, "folder '" + existing.string() + "' is not writable");
    if (existing == fs::path(folder))
        remove_stale_temporaries(existing);
}

// This host's mark in the temporaries' names: its name's FNV-1a hash, in hex, found once.
static const std::string &host_mark() {
    static const std::string mark = [] {
        char host[256] = {};
        ::gethostname(host, sizeof host - 1);
        std::uint32_t h = 2166136261u;
        for (const char *c = host; *c; ++c)
            h = (h ^ std::uint8_t(*c)) * 16777619u;
        char text[16];
        std::snprintf(text, sizeof text, "%08x", h);
        return std::string(text);
    }();
    return mark;
}

// ".<name>.tinlod-<host>-<pid>-<random>.tmp<extension>": the host and the process that write it,
// so that a later process can tell one whose writer was killed (remove_stale_temporaries).
// Appended piece by piece: GCC 12 at -O3 warns (-Wrestrict, a false positive) on the inlined
// `"." + std::string` of the one-line form.
static std::string hidden_name(const fs::path &target) {
    std::random_device rd;
    std::string name = ".";
    name += target.filename().string();
    name += ".tinlod-";
    name += host_mark();
    name += '-';
    name += std::to_string(::getpid());
    name += '-';
    name += std::to_string(rd());
    name += ".tmp";
    name += target.extension().string();
    return name;
}

// Removes from `folder` the temporaries (files, or a StagedFolder's staging folders) that a tinlod
// process of this host left when it was killed (SIGKILL, a crash, a power cut) before it could
// remove them: those whose process no longer runs. Another host's, and a running process's, stay.
static void remove_stale_temporaries(const fs::path &folder) {
    const std::string mark = ".tinlod-" + host_mark() + "-";
    std::error_code ec;
    for (const fs::directory_entry &e : fs::directory_iterator(folder, ec)) {
        const std::string name = e.path().filename().string();
        const std::size_t at = name.rfind(mark);
        if (name[0] != '.' || at == std::string::npos || at == 0)
            continue;
        // <pid>-<random>.tmp after the mark
        const auto digit = [](const char *c) {
            return std::isdigit(static_cast<unsigned char>(*c));
        };
        const char *p = name.c_str() + at + mark.size();
        char *end = nullptr;
        if (!digit(p))
            continue;
        const long pid = std::strtol(p, &end, 10);
        if (*end != '-' || !digit(end + 1))
            continue;
        std::strtoul(end + 1, &end, 10);
        if (std::strncmp(end, ".tmp", 4) != 0)
            continue;
        if (pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH)
            fs::remove_all(e.path(), ec);
    }
}

void write_atomically(const std::string &path,
                      const std::function<void(const std::string &)> &write) {
    const Target target = check_output(path);
    if (target.stream) {
        write(target.file.string());
        return;
    }
    const fs::path folder = folder_of(target.file);
    remove_stale_temporaries(folder);
    const fs::path tmp = folder / hidden_name(target.file);
    std::error_code ec;
    const Deferral deferral;
    try {
        write(tmp.string());
        check_interrupt();
        fs::rename(tmp, target.file);
    } catch (...) {
        fs::remove(tmp, ec);
        throw;
    }
}

StagedFolder::StagedFolder(const std::string &folder) : folder_(folder) {
    std::error_code ec;
    for (fs::path p(folder); !p.empty() && !fs::exists(p, ec); p = p.parent_path())
        created_.push_back(p);
    if (!created_.empty()) {
        check_writable_folder(folder);
        if (!fs::create_directories(folder, ec))
            throw Error(folder, "cannot create the folder: " + ec.message());
    }
    check_folder(folder, folder, "folder");
    remove_stale_temporaries(folder);
    const fs::path staging = fs::path(folder) / hidden_name("staged");
    if (!fs::create_directory(staging, ec))
        throw Error(folder, "cannot create a staging folder in it: " + ec.message());
    staging_ = staging.string();
}

StagedFolder::~StagedFolder() {
    std::error_code ec;
    fs::remove_all(staging_, ec);
    // The folders created for nothing, from the innermost, unless something else entered them.
    for (const fs::path &p : created_)
        fs::remove(p, ec);
}

void StagedFolder::write(const std::string &name,
                         const std::function<void(const std::string &)> &write) {
    assert(fs::path(name).filename() == name);
    const std::string staged = (fs::path(staging_) / name).string();
    try {
        write(staged);
    } catch (const Error &e) {
        if (e.subject() != staged)
            throw;
        throw Error((fs::path(folder_) / name).string(), e.reason());
    }
    names_.push_back(name);
}

void StagedFolder::commit() {
    check_interrupt();
    std::error_code ec;
    for (const std::string &name : names_)
        if (fs::is_directory(fs::path(folder_) / name, ec))
            throw Error((fs::path(folder_) / name).string(), "output path is a folder");
    for (const std::string &name : names_) {
        fs::rename(fs::path(staging_) / name, fs::path(folder_) / name, ec);
        if (ec)
            throw Error((fs::path(folder_) / name).string(), "cannot move in: " + ec.message());
    }
    names_.clear();
    created_.clear();
}

double peak_rss_mb() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0)
            return std::stod(line.substr(6)) / 1024.0;
    return 0.0;
}

void advise_huge_pages(const void *data, std::size_t bytes) {
    constexpr std::uintptr_t huge = std::uintptr_t(2) << 20;
    const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + huge - 1) & ~(huge - 1);
    const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(huge - 1);
    if (end <= begin)
        return;
#ifdef MADV_HUGEPAGE
    void *start = reinterpret_cast<void *>(begin);
    if (madvise(start, end - begin, MADV_HUGEPAGE) != 0)
        return;
    madvise(start, end - begin, MADV_COLLAPSE);
#endif
}

static std::atomic<int> g_max_threads{0}; // 0: the hardware concurrency

void set_max_threads(int threads) {
    assert(threads >= 1);
    g_max_threads = threads;
}

int max_threads() {
    const int n = g_max_threads;
    return n > 0 ? n : int(std::max(1u, std::thread::hardware_concurrency()));
}

Progress::Progress(std::string label, std::int64_t total)
    : label_(std::move(label)), total_(total), active_(::isatty(STDERR_FILENO) != 0),
      deferral_(std::make_unique<Deferral>()) {}

Progress::~Progress() {
    if (active_ && !finished_ && last_percent_ >= 0)
        std::fputc('\n', stderr);
}

void Progress::update(std::int64_t done) {
    check_interrupt();
    if (!active_ || total_ <= 0)
        return;
    const int percent = static_cast<int>(100 * std::min(done, total_) / total_);
    if (percent == last_percent_)
        return;
    last_percent_ = percent;
    const int width = 30;
    const int filled = percent * width / 100;
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), filled,
                 "==============================", width - filled, "", percent);
    std::fflush(stderr);
}

void Progress::finish() {
    update(total_);
    deferral_.reset();
    check_interrupt(); // one that came after the last update
    if (active_ && last_percent_ >= 0 && !finished_)
        std::fputc('\n', stderr);
    finished_ = true;
}

} // namespace tinlod
