// Fuzz target: the raster reader (our OpenImageIO/libgeotiff wrapper, Terrain-RGB, .hgt naming).
// The first byte picks the extension and the decoding; the rest is the file.
#include "fuzz_input.hpp"

#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1)
        return 0;
    static const char* k_ext[] = {".tif", ".png", ".exr", ".hgt"};
    const int pick = data[0] % 8;
    const std::string path = tinlod::fuzz::write_input(data + 1, size - 1, k_ext[pick % 4]);
    tinlod::LoadOptions options;
    options.terrain_rgb = pick >= 4;
    try {
        const tinlod::Heightfield hf = tinlod::load_heightfield(path, options);
        if (hf.width < 2 || hf.height < 2 || hf.z.size() != std::size_t(hf.width) * hf.height)
            __builtin_trap();
    } catch (const tinlod::Error&) {
    }
    std::remove(path.c_str());
    return 0;
}
