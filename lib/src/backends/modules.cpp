// The command line's backends (backends.hpp): each opened from its module, tinlod_NAME.so in
// TINLOD_MODULES_FROM_BIN (relative to the folder of the running program: lib/tinlod beside bin,
// in the build tree as in an install), the first time it is asked for.
#include "backends.hpp"
#include "tinlod/error.hpp"
#include "tinlod/util.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>

namespace tinlod::backends {

namespace {

// Where the modules are: from the program's own path, so that a moved install still finds them.
std::string module_path(const char *name) {
    std::error_code ec;
    const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
    return (program.parent_path() / TINLOD_MODULES_FROM_BIN / (std::string(name) + ".so"))
        .lexically_normal()
        .string();
}

// The backend a module exports as `entry`, loaded once; throws Error naming the module when it is
// missing or broken (a partial install, a library of the wrong version).
template <typename Backend> Backend &load(const char *name, const char *entry, const char *what) {
    static std::once_flag once;
    static Backend *backend = nullptr;
    static std::string path, failure;
    std::call_once(once, [&] {
        path = module_path(name);
        void *handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        const auto make = handle ? reinterpret_cast<Backend *(*)()>(dlsym(handle, entry)) : nullptr;
        if (make) {
            backend = make();
            return;
        }
        // dlerror() names the file first, as the error line does.
        const char *error = dlerror();
        std::string why = error ? error : "";
        if (why.rfind(path + ": ", 0) == 0)
            why.erase(0, path.size() + 2);
        failure = std::string("tinlod's module for ") + what + " is missing or broken (" +
                  (why.empty() ? "no entry point" : why) + "); reinstall tinlod";
    });
    if (!backend)
        throw Error(path, failure);
    return *backend;
}

} // namespace

ImageFiles &image_files() {
    ImageFiles &b = load<ImageFiles>("tinlod_oiio", "tinlod_oiio_backend", "image files");
    b.set_threads(max_threads());
    return b;
}

TiffFiles &tiff_files() { return load<TiffFiles>("tinlod_tiff", "tinlod_tiff_backend", "TIFF"); }

PngFiles &png_files() { return load<PngFiles>("tinlod_png", "tinlod_png_backend", "PNG"); }

CrsLibrary &crs_library() {
    return load<CrsLibrary>("tinlod_proj", "tinlod_proj_backend", "coordinate systems");
}

} // namespace tinlod::backends
