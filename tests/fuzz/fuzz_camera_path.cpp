// Fuzz target: the camera path CSV parser.
#include "tinlod/camera_path.hpp"
#include "tinlod/error.hpp"

#include <cmath>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    try {
        const tinlod::CameraPath path = tinlod::parse_camera_path(
            std::string(reinterpret_cast<const char *>(data), size), "fuzz");
        for (std::size_t i = 1; i < path.keys.size(); ++i)
            if (!(path.keys[i].t > path.keys[i - 1].t))
                __builtin_trap();
        const tinlod::View v = path.at_time(path.keys.front().t + path.duration() / 2, {});
        if (!std::isfinite(v.eye.x))
            __builtin_trap();
    } catch (const tinlod::Error &) {
    }
    return 0;
}
