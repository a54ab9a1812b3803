// Fuzz target: the raster reader (our OpenImageIO/libgeotiff wrapper, Terrain-RGB, .hgt).
// The first byte, modulo 7, picks the extension and the decoding (seeds:
// scripts/make_fuzz_seeds.py): 0-2 .tif .png .exr, 4-6 the same decoded as Terrain-RGB, 3 .hgt.
// An SRTM tile is 2.9 MB, beyond any fuzz input, so .hgt here reaches the size check only; its
// decoding has its own target, fuzz_hgt, as one tile costs a hundred small rasters.
// The rest is the file.
#include "fuzz_input.hpp"

#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <string>

extern "C" int LLVMFuzzerInitialize(int *, char ***) {
    // Only the reader the extension names: the fallback through every other OpenImageIO plugin
    // (DICOM, HEIF, ...) fuzzes OpenImageIO, not our wrapper, at many times the cost per input.
    OIIO::attribute("try_all_readers", 0);
    OIIO::attribute("threads", 1);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    if (size < 1)
        return 0;
    static const char *k_ext[] = {".tif", ".png", ".exr", ".hgt"};
    const int pick = data[0] % 7;
    const std::string path = tinlod::fuzz::write_input(data + 1, size - 1, k_ext[pick % 4]);
    tinlod::LoadOptions options;
    options.terrain_rgb = pick >= 4;
    // Rasters whose load needs more are refused before any allocation, as too large for this
    // machine would be: a header may declare any size, and the buffers of a large raster cost
    // far more than decoding a small one.
    options.max_memory_mb = 2;
    try {
        const tinlod::Heightfield hf = tinlod::load_heightfield(path, options);
        if (hf.width < 2 || hf.height < 2 || hf.z.size() != std::size_t(hf.width) * hf.height)
            __builtin_trap();
        if (!(std::isfinite(hf.dx) && hf.dx > 0 && std::isfinite(hf.dy) && hf.dy > 0))
            __builtin_trap();
    } catch (const tinlod::Error &) {
    }
    std::remove(path.c_str());
    return 0;
}
