// The Heightfield's own members (raster.hpp), in tinlod::core; its loaders are tinlod::io's.
#include "tinlod/raster.hpp"

#include <algorithm>

namespace tinlod {

float Heightfield::min_z() const { return z.empty() ? 0.f : *std::min_element(z.begin(), z.end()); }
float Heightfield::max_z() const { return z.empty() ? 0.f : *std::max_element(z.begin(), z.end()); }

} // namespace tinlod
