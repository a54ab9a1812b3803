// The version and licence both programs print with `--version`: the one definition of them.
#pragma once

#include <string>

namespace tinlod {

inline constexpr const char *k_version = "0.1.0";
inline constexpr const char *k_licence = "BSD-3-Clause"; // see LICENSE

// "PROGRAM VERSION (LICENCE)", e.g. "tinlod 0.1.0 (BSD-3-Clause)".
inline std::string version_line(const std::string &program) {
    return program + " " + k_version + " (" + k_licence + ")";
}

} // namespace tinlod
