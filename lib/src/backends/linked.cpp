// The backends of the installed libraries (backends.hpp): linked in, ready at once.
#include "backends.hpp"
#include "tinlod/util.hpp"

namespace tinlod::backends {

ImageFiles &image_files() {
    ImageFiles &b = *tinlod_oiio_backend();
    b.set_threads(max_threads());
    return b;
}

TiffFiles &tiff_files() { return *tinlod_tiff_backend(); }
PngFiles &png_files() { return *tinlod_png_backend(); }
CrsLibrary &crs_library() { return *tinlod_proj_backend(); }

} // namespace tinlod::backends
