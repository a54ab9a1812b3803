// Test helpers: the bundled real assets in meshes/, running the CLI, and TIN invariants.
#pragma once

#include "tinlod/raster.hpp"
#include "tinlod/render.hpp"
#include "tinlod/tin.hpp"

#include <sys/types.h>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace tinlod::test {

// Absolute path of a file in meshes/.
std::string asset(const std::string &name);
// The w x h samples of `hf` from column x0, row y0 (a crop of a real DEM for a small test); the
// void mask is dropped.
Heightfield crop(const Heightfield &hf, int x0, int y0, int w, int h);
// A square crop of a bundled DEM and a vertical bound: the real cases the erase's tests run on.
struct CropCase {
    const char *file; // in meshes/
    int x0, y0, side;
    double bound;
    Heightfield load() const; // crop(load_heightfield(asset(file)), x0, y0, side, side)
    std::string name() const; // "FILE at BOUND", for SCOPED_TRACE
};
// A fresh empty temporary folder for this test (removed at exit).
std::string temp_dir();
// The bytes of the file at `path` (empty when it cannot be read).
std::string file_bytes(const std::string &path);
// Every file under `dir` (hidden ones too), by its path inside it, with its bytes.
std::map<std::string, std::string> files_under(const std::string &dir);

// The bytes of a 2 x 2 int16 GeoTIFF (heights 100, 200 in the north row, 300, 400 in the south):
// `georef` holds TIFF tags with their doubles, in ascending tag order (33550 pixel scale, 33922
// tie points, 34264 model transformation), `keys` the GeoKey directory (tag 34735), `nodata`
// (unless empty) the GDAL_NODATA text (tag 42113).
std::string geotiff_bytes(const std::vector<std::pair<unsigned, std::vector<double>>> &georef,
                          const std::vector<unsigned> &keys, const std::string &nodata = "");

// The bytes of a w x h int16 TIFF in tiles of tile_w x tile_h samples, of which only the first
// is stored (8 bytes): a header may declare tiles of any size.
std::string tiled_tiff_bytes(unsigned w, unsigned h, unsigned tile_w, unsigned tile_h);

// The bytes of a PNG of w x h pixels of colour type `color_type` (0 grey, 2 RGB, 3 palette,
// 4 grey+alpha, 6 RGBA) and `bit_depth` 8 or 16: `samples` row-major, north row first, channels
// interleaved. `chunks` (type, data), e.g. a tRNS or PLTE, go before the image data. With
// `samples` empty the image data stops after a few bytes: a file that declares its size and
// holds almost nothing. Uncompressed (stored deflate blocks), so nothing but the bytes is needed.
std::string png_bytes(int w, int h, int color_type, int bit_depth,
                      const std::vector<unsigned> &samples,
                      const std::vector<std::pair<std::string, std::string>> &chunks = {});

struct RunResult {
    int status = 0;
    std::string out; // stdout
    std::string err; // stderr
};
// Runs the tinlod CLI with `args` (a shell-quoted string); status 124 when it hung (> 120 s,
// 900 s in a sanitizer build). `max_file_bytes` > 0: files it writes are limited to that size, a
// write past it failing (EFBIG) as a write on a full disk does.
RunResult run_cli(const std::string &args, std::uint64_t max_file_bytes = 0);

// Starts the tinlod CLI with `args` (not through a shell), its stdout to /dev/null and its
// stderr to `err_file` (/dev/null when empty), with the default action for every interrupt signal.
// Returns its process id.
pid_t start_cli(const std::vector<std::string> &args, const std::string &err_file = "");

// Invariants of a TIN: every edge manifold (<= 2 faces, OpenMesh guarantees it for a valid mesh),
// every face counter-clockwise seen from above with positive xy area. Returns the number of faces
// that violate the orientation (0 for a valid TIN).
std::int64_t count_folded_faces(const Mesh &mesh);
// Sum of the xy areas of the live faces.
double xy_area(const Mesh &mesh);

// Whether pixel `pixel` of `image` is the background `options` clear to, up to one level of
// rounding per channel.
bool is_sky(const Image &image, std::size_t pixel, const RenderOptions &options = {});

} // namespace tinlod::test

// Skips the test (GoogleTest) where no OpenGL context can be made, saying why.
#define REQUIRE_RENDER()                                                                           \
    do {                                                                                           \
        std::string why;                                                                           \
        if (!tinlod::render_available(&why))                                                       \
            GTEST_SKIP() << "no OpenGL context: " << why;                                          \
    } while (0)
