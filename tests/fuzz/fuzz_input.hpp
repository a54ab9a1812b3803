// Shared by the fuzz targets: the input bytes as a file with a chosen extension, since the
// readers under test take paths.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace tinlod::fuzz {

inline std::string write_input(const std::uint8_t *data, std::size_t size, const char *ext) {
    const std::string path = "/tmp/tinlod-fuzz-" + std::to_string(::getpid()) + ext;
    if (FILE *f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    return path;
}

} // namespace tinlod::fuzz
