// Float rounding: a double rounded to a float in a chosen direction, the one definition used
// wherever a bound is stored as a float (the erase, the refiner, the quad-tree retrieval), and
// the margin by which float corners can move a TIN triangle's plane.
#pragma once

#include <algorithm>
#include <cmath>

namespace tinlod {

// The nearest float at or above (below) d: a bound stored as float is never understated
// (overstated).
inline float float_up(double d) {
    const float f = float(d);
    return double(f) < d ? std::nextafter(f, INFINITY) : f;
}

inline float float_down(double d) {
    const float f = float(d);
    return double(f) > d ? std::nextafter(f, -INFINITY) : f;
}

// What rounding every corner of a TIN triangle of this slope (|grad z|) to float can move its
// interpolant at a point whose largest coordinate magnitude is `coord`: a few ulp of it. The mesh
// holds float coordinates of exact grid positions, so deviations are widened by this.
inline double rounding_margin(double coord, double slope) {
    const double ulp = 1.2e-7 * std::max(coord, 1.0);
    return 4.0 * ulp * slope;
}

} // namespace tinlod
