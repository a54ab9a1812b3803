// Small shared services: atomic file writes, timing, peak memory, progress bar, the thread count.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace tinlod {

// Thrown by check_interrupt() once SIGINT, SIGTERM or SIGHUP came (with interrupt handlers
// installed): unwinding removes temporaries and staged files as any error does.
class Interrupted : public std::runtime_error {
  public:
    explicit Interrupted(int signal) : std::runtime_error("interrupted"), signal_(signal) {}
    int signal() const { return signal_; }

  private:
    int signal_;
};

// From here on SIGINT, SIGTERM and SIGHUP (those not ignored when the process started, as nohup
// and a shell's background jobs do) end the process at once, as by default, except while
// a Deferral lives: then they only set a flag, which check_interrupt() turns into Interrupted where
// unwinding is safe, so that a command stopped by Ctrl-C leaves no partial output. A Progress
// (until finish()), a StagedFolder and write_atomically defer them and check. A second signal ends
// the process at once.
void install_interrupt_handlers();

// Throws Interrupted when a signal came while a Deferral lived.
void check_interrupt();

// See install_interrupt_handlers.
class Deferral {
  public:
    Deferral();
    ~Deferral();
    Deferral(const Deferral &) = delete;
    Deferral &operator=(const Deferral &) = delete;
};

// Writes `path` by calling write(tmp) on a temporary in the same folder, then renaming it over
// `path`. On any exception the temporary is removed and the exception rethrown; `path` is never
// left half-written. A symbolic link is followed: the file it names (or would name, when dangling,
// as a shell's `>` does) is replaced in its own folder, and the link stays. A stream (is_stream) is
// written to directly: write(path), with no temporary. Throws Error when the folder is missing or
// not writable, or `path` is a folder, a block device or a socket. The temporaries that killed
// tinlod processes left in the folder are removed first (see check_writable).
void write_atomically(const std::string &path,
                      const std::function<void(const std::string &)> &write);

// Whether write_atomically writes `path` directly: when it is `-` (the standard output), or names,
// through its symbolic links, a character device (/dev/null, a terminal), a FIFO, or an open file
// descriptor (/dev/stdout, /dev/fd/N), whatever that descriptor is open on.
bool is_stream(const std::string &path);

// Makes `-` name what the standard output is open on now, and points the standard output (file
// descriptor 1) at the standard error: a command that writes an output to `-` keeps its own
// messages out of it. Where that cannot be done (no file descriptor left), nothing changes.
void divert_standard_output();

// Whether output paths `a` and `b` name the same file: through symbolic links and other spellings
// of its folder (`./x`, `dir/../x`), existing or not. Two names of one character device do not
// count (writing both to /dev/null or a terminal loses nothing). Empty paths, and those that cannot
// be outputs (check_writable tells why), name no file.
bool same_output(const std::string &a, const std::string &b);

// Throws Error naming the first of `paths` that write_atomically would refuse (empty paths are
// skipped), for a command to make those checks on all its outputs before its work rather than on
// each after it. It also removes, from the folders of these paths, the temporaries (files and
// StagedFolder staging folders) that tinlod processes of this host killed by SIGKILL or a crash
// left behind (those whose process no longer runs).
void check_writable(const std::vector<std::string> &paths);

// Throws Error when `folder` cannot hold a StagedFolder: it exists and is not a writable folder, or
// it is missing and the nearest folder above it that exists is not writable. Removes the
// temporaries of killed processes in it, as check_writable does for files.
void check_writable_folder(const std::string &folder);

// Files written into a folder all together or not at all, as a flight's frames: each is written
// into a hidden staging folder inside it, and commit() moves them in. Destroyed before commit() (an
// error midway), it removes what it staged and leaves the folder as it was: a folder it created is
// removed again. It defers interrupt signals (see install_interrupt_handlers), and commit() first
// checks for one.
class StagedFolder {
  public:
    // Creates `folder` (and the folders above it) when missing. Throws Error naming `folder` when
    // it is not a writable folder or cannot be created.
    explicit StagedFolder(const std::string &folder);
    ~StagedFolder();
    StagedFolder(const StagedFolder &) = delete;
    StagedFolder &operator=(const StagedFolder &) = delete;
    // Writes the file `name` (a bare file name) by calling write(path) with the path to write it
    // to; it enters the folder at commit(). An Error that names that path names the file's place
    // in the folder instead.
    void write(const std::string &name, const std::function<void(const std::string &)> &write);
    // Moves the staged files in, over files of the same names. Throws Error, having moved none,
    // when a name is taken by a folder.
    void commit();

  private:
    Deferral deferral_;
    std::string folder_, staging_;
    std::vector<std::filesystem::path> created_; // folders the constructor made, innermost first
    std::vector<std::string> names_;
};

// Peak resident set size of this process, MiB (VmHWM).
double peak_rss_mb();

// Asks the kernel to back the 2 MiB pages inside [data, data + bytes) with huge pages, now (Linux:
// MADV_HUGEPAGE, then MADV_COLLAPSE; nothing where either is refused). For large arrays read at
// random for a long time, where 4 KiB pages cost a TLB miss per read.
void advise_huge_pages(const void *data, std::size_t bytes);

// Threads the library may run at once: its own workers (the quad-tree build, Hausdorff distances)
// and OpenImageIO's and OpenEXR's pools (tinlod::io and tinlod::render apply it before each use).
// `threads` >= 1; the default is the hardware concurrency. Set it before the work starts (the CLI's
// --threads), not while a pool runs.
void set_max_threads(int threads);
int max_threads();

class Stopwatch {
  public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    double ms() const {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
            .count();
    }
    void reset() { start_ = std::chrono::steady_clock::now(); }

  private:
    std::chrono::steady_clock::time_point start_;
};

// A progress bar on stderr, drawn only when stderr is a terminal; cheap to call often. It defers
// interrupt signals until finish(), and each update (and finish()) calls check_interrupt().
class Progress {
  public:
    Progress(std::string label, std::int64_t total);
    ~Progress();
    void update(std::int64_t done);
    void finish();

  private:
    std::string label_;
    std::int64_t total_;
    int last_percent_ = -1;
    bool active_;
    bool finished_ = false;
    std::unique_ptr<Deferral> deferral_; // until finish()
};

} // namespace tinlod
