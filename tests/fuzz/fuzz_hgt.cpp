// Fuzz target: SRTM .hgt decoding (lib/raster): the file name names the SW corner ([NS]dd[EW]ddd),
// the samples are big-endian int16 with voids at -32768. The first 7 input bytes are the file name
// (bytes that are not letters or digits map to "NSEW0123456789"); the rest, repeated, fills a
// 1201x1201 tile, so short inputs make tiles of repeating voids, ramps and spikes.
#include "tinlod/error.hpp"
#include "tinlod/raster.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
    std::string stem;
    for (std::size_t i = 0; i < 7; ++i) {
        const unsigned char b = i < size ? data[i] : '0';
        stem += std::isalnum(b) ? char(b) : "NSEW0123456789"[b % 14];
    }
    const std::size_t skip = std::min<std::size_t>(size, 7);
    data += skip;
    size -= skip;
    std::vector<std::uint8_t> tile(std::size_t(1201) * 1201 * 2, 0);
    if (size > 0) {
        std::copy(data, data + std::min(size, tile.size()), tile.begin());
        for (std::size_t done = size; done < tile.size(); done *= 2)
            std::copy_n(tile.begin(), std::min(done, tile.size() - done), tile.begin() + done);
    }
    const std::string dir = "/tmp/tinlod-fuzz-" + std::to_string(::getpid());
    ::mkdir(dir.c_str(), 0700);
    const std::string path = dir + "/" + stem + ".hgt";
    if (FILE *f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(tile.data(), 1, tile.size(), f);
        std::fclose(f);
    }
    try {
        const tinlod::Heightfield hf = tinlod::load_heightfield(path);
        if (hf.width < 2 || hf.height < 2 || hf.z.size() != std::size_t(hf.width) * hf.height)
            __builtin_trap();
        if (!(std::isfinite(hf.dx) && hf.dx > 0 && std::isfinite(hf.dy) && hf.dy > 0))
            __builtin_trap();
        for (float z : hf.z)
            if (!(z >= -32767 && z <= 32767))
                __builtin_trap(); // a void left unfilled, or a fill outside the valid heights
    } catch (const tinlod::Error &) {
    }
    std::remove(path.c_str());
    std::remove(dir.c_str());
    return 0;
}
