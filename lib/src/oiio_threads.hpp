// OpenImageIO's and OpenEXR's thread pools follow max_threads() (util.hpp): the io and render
// modules apply it before each use, since tinlod::core, which holds the limit, links no
// OpenImageIO.
#pragma once

#include "tinlod/util.hpp"

#include <OpenImageIO/imageio.h>

namespace tinlod {

inline void limit_oiio_threads() {
    const int threads = max_threads();
    OIIO::attribute("threads", threads);
    OIIO::attribute("exr_threads", threads);
}

} // namespace tinlod
