// The DEMs of a tile set as one lattice in longitude and latitude (tiles.hpp: load_coverage).
#include "crs.hpp"

#include "tinlod/error.hpp"
#include "tinlod/tiles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tinlod {

namespace {

// Posts of a lattice whose spacing and origin come from one DEM's grid, transformed; the same
// grid within this share of a spacing counts as one.
constexpr double k_same_grid = 1e-6;

bool is_whole(double x) { return std::abs(x - std::round(x)) <= k_same_grid; }

// Every DEM in EPSG:4326 on the first one's grid: the lattice is their samples.
bool on_one_grid(const std::vector<Heightfield> &dems) {
    const Heightfield &a = dems[0];
    for (const Heightfield &d : dems)
        if (d.native_epsg != 4326 || !d.native_geographic ||
            std::abs(d.native_dx - a.native_dx) > k_same_grid * a.native_dx ||
            std::abs(d.native_dy - a.native_dy) > k_same_grid * a.native_dy ||
            !is_whole((d.native_x0 - a.native_x0) / a.native_dx) ||
            !is_whole((d.native_y0 - a.native_y0) / a.native_dy))
            return false;
    return true;
}

void check_size(const std::string &subject, std::int64_t w, std::int64_t h) {
    if (w <= 0 || h <= 0 || w > k_max_raster_samples / h)
        throw Error(subject, "the DEMs' union is " + std::to_string(w) + " x " + std::to_string(h) +
                                 " posts, beyond the supported maximum of 2^31");
}

GeoLattice mosaic(const std::vector<Heightfield> &dems) {
    const Heightfield &a = dems[0];
    std::int64_t i0 = std::numeric_limits<std::int64_t>::max(), j0 = i0, i1 = -i0, j1 = -i0;
    std::vector<std::pair<std::int64_t, std::int64_t>> offsets;
    for (const Heightfield &d : dems) {
        const auto oi = std::int64_t(std::llround((d.native_x0 - a.native_x0) / a.native_dx));
        const auto oj = std::int64_t(std::llround((d.native_y0 - a.native_y0) / a.native_dy));
        offsets.emplace_back(oi, oj);
        i0 = std::min(i0, oi), j0 = std::min(j0, oj);
        i1 = std::max(i1, oi + d.width), j1 = std::max(j1, oj + d.height);
    }
    check_size("coverage", i1 - i0, j1 - j0);
    GeoLattice g;
    g.dlon = a.native_dx, g.dlat = a.native_dy;
    g.lon0 = a.native_x0 + double(i0) * g.dlon;
    g.lat0 = a.native_y0 + double(j0) * g.dlat;
    g.width = int(i1 - i0), g.height = int(j1 - j0);
    g.z.assign(std::size_t(g.width) * std::size_t(g.height), NAN);
    // Where DEMs overlap (adjacent SRTM tiles share a row or column) the first one given wins.
    for (std::size_t k = 0; k < dems.size(); ++k) {
        const Heightfield &d = dems[k];
        for (int r = 0; r < d.height; ++r)
            for (int c = 0; c < d.width; ++c) {
                float &post = g.z[std::size_t(r + offsets[k].second - j0) * std::size_t(g.width) +
                                  std::size_t(c + offsets[k].first - i0)];
                if (std::isnan(post))
                    post = d.at(c, r);
            }
    }
    return g;
}

// A DEM's footprint in longitude/latitude: its outline's points, transformed.
GeoRect footprint(const Heightfield &d, const std::string &path) {
    std::vector<glm::dvec2> outline;
    const int steps = 64;
    for (int k = 0; k <= steps; ++k) {
        const double c = double(d.width - 1) * k / steps, r = double(d.height - 1) * k / steps;
        for (const glm::dvec2 &p : {glm::dvec2(c, 0), glm::dvec2(c, d.height - 1), glm::dvec2(0, r),
                                    glm::dvec2(d.width - 1, r)})
            outline.emplace_back(d.native_x0 + p.x * d.native_dx, d.native_y0 + p.y * d.native_dy);
    }
    const auto geo = crs::Transformation(path, d.native_epsg, 4326).apply(outline);
    GeoRect box{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const glm::dvec2 &p : geo) {
        if (std::isnan(p.x))
            throw Error(path, "its outline does not transform to longitude and latitude");
        box.west = std::min(box.west, p.x), box.east = std::max(box.east, p.x);
        box.south = std::min(box.south, p.y), box.north = std::max(box.north, p.y);
    }
    if (box.west < -180.0 - 1e-9 || box.east > 180.0 + 1e-9 || box.south < -90.0 - 1e-9 ||
        box.north > 90.0 + 1e-9)
        throw Error(path, "lies beyond longitudes -180..180 or latitudes -90..90");
    return box;
}

// A DEM's spacing in degrees at its centre: its own for a geographic CRS, else the steps of one
// sample east and north, transformed.
glm::dvec2 spacing_degrees(const Heightfield &d, const std::string &path) {
    if (d.native_geographic)
        return {d.native_dx, d.native_dy};
    const glm::dvec2 c(d.native_x0 + 0.5 * (d.width - 1) * d.native_dx,
                       d.native_y0 + 0.5 * (d.height - 1) * d.native_dy);
    const std::vector<glm::dvec2> pts{c, c + glm::dvec2(d.native_dx, 0),
                                      c + glm::dvec2(0, d.native_dy)};
    const auto geo = crs::Transformation(path, d.native_epsg, 4326).apply(pts);
    const glm::dvec2 s(glm::length(geo[1] - geo[0]), glm::length(geo[2] - geo[0]));
    if (!(s.x > 0.0) || !(s.y > 0.0))
        throw Error(path, "its spacing does not transform to degrees");
    return s;
}

// Each post takes the bilinear interpolation of the first DEM whose samples surround it.
GeoLattice warp(const std::vector<Heightfield> &dems, const std::vector<std::string> &paths) {
    std::vector<GeoRect> boxes;
    glm::dvec2 step(INFINITY);
    GeoRect all{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (std::size_t k = 0; k < dems.size(); ++k) {
        boxes.push_back(footprint(dems[k], paths[k]));
        step = glm::min(step, spacing_degrees(dems[k], paths[k]));
        all.west = std::min(all.west, boxes[k].west), all.east = std::max(all.east, boxes[k].east);
        all.south = std::min(all.south, boxes[k].south);
        all.north = std::max(all.north, boxes[k].north);
    }
    // Aligned to the first DEM's south-west sample, so a geographic DEM keeps its own grid.
    const auto sw = crs::Transformation(paths[0], dems[0].native_epsg, 4326)
                        .apply(std::vector{glm::dvec2(dems[0].native_x0, dems[0].native_y0)})[0];
    GeoLattice g;
    g.resampled = true;
    g.dlon = step.x, g.dlat = step.y;
    g.lon0 = sw.x - std::ceil((sw.x - all.west) / g.dlon - k_same_grid) * g.dlon;
    g.lat0 = sw.y - std::ceil((sw.y - all.south) / g.dlat - k_same_grid) * g.dlat;
    const auto w = std::int64_t(std::floor((all.east - g.lon0) / g.dlon + k_same_grid)) + 1;
    const auto h = std::int64_t(std::floor((all.north - g.lat0) / g.dlat + k_same_grid)) + 1;
    check_size("coverage", w, h);
    g.width = int(w), g.height = int(h);
    g.z.assign(std::size_t(w) * std::size_t(h), NAN);
    for (std::size_t k = 0; k < dems.size(); ++k) {
        const Heightfield &d = dems[k];
        const auto i0 =
            std::max<std::int64_t>(0, std::int64_t(std::floor((boxes[k].west - g.lon0) / g.dlon)));
        const auto i1 = std::min<std::int64_t>(
            w - 1, std::int64_t(std::ceil((boxes[k].east - g.lon0) / g.dlon)));
        const auto j0 =
            std::max<std::int64_t>(0, std::int64_t(std::floor((boxes[k].south - g.lat0) / g.dlat)));
        const auto j1 = std::min<std::int64_t>(
            h - 1, std::int64_t(std::ceil((boxes[k].north - g.lat0) / g.dlat)));
        const crs::Transformation to_dem(paths[k], 4326, d.native_epsg);
        std::vector<glm::dvec2> row;
        for (std::int64_t j = j0; j <= j1; ++j) {
            row.clear();
            for (std::int64_t i = i0; i <= i1; ++i)
                row.emplace_back(g.lon(i), g.lat(j));
            const auto native = to_dem.apply(row);
            for (std::int64_t i = i0; i <= i1; ++i) {
                float &post = g.z[std::size_t(j) * std::size_t(w) + std::size_t(i)];
                const glm::dvec2 p = native[std::size_t(i - i0)];
                if (!std::isnan(post) || std::isnan(p.x))
                    continue;
                double c = (p.x - d.native_x0) / d.native_dx, r = (p.y - d.native_y0) / d.native_dy;
                // A post within float noise of the DEM's outline is on it.
                if (std::abs(c - std::round(c)) <= k_same_grid)
                    c = std::round(c);
                if (std::abs(r - std::round(r)) <= k_same_grid)
                    r = std::round(r);
                if (c < 0 || r < 0 || c > d.width - 1 || r > d.height - 1)
                    continue;
                const int c0 = std::min(int(c), d.width - 2), r0 = std::min(int(r), d.height - 2);
                const double tc = c - c0, tr = r - r0;
                const double south = (1 - tc) * d.at(c0, r0) + tc * d.at(c0 + 1, r0);
                const double north = (1 - tc) * d.at(c0, r0 + 1) + tc * d.at(c0 + 1, r0 + 1);
                post = float((1 - tr) * south + tr * north);
            }
        }
    }
    return g;
}

} // namespace

GeoLattice load_coverage(const std::vector<std::string> &paths, const LoadOptions &options) {
    std::vector<Heightfield> dems;
    for (const std::string &path : paths) {
        dems.push_back(load_heightfield(path, options));
        const Heightfield &d = dems.back();
        if (d.native_epsg == 0)
            throw Error(path, "has no georeferencing with an EPSG code: where its tiles lie on "
                              "Earth is unknown");
        if (d.width < 2 || d.height < 2)
            throw Error(path, "needs at least 2 x 2 samples");
    }
    GeoLattice g = on_one_grid(dems) ? mosaic(dems) : warp(dems, paths);
    // Longitudes run -180..180 in the tiling scheme (a file in 0..360 is not moved).
    constexpr double k_slack = 1e-9;
    if (g.lon(0) < -180.0 - k_slack || g.lon(g.width - 1) > 180.0 + k_slack ||
        g.lat(0) < -90.0 - k_slack || g.lat(g.height - 1) > 90.0 + k_slack)
        throw Error(paths[0], "the DEMs reach beyond longitudes -180..180 or latitudes -90..90");
    for (const float h : g.z)
        g.covered += std::isnan(h) ? 0 : 1;
    if (g.covered == 0)
        throw Error(paths[0], "no lattice post falls inside the DEMs");
    return g;
}

int default_max_zoom(const GeoLattice &lattice) {
    const double finest = std::min(lattice.dlon, lattice.dlat);
    int z = 0;
    while (z < k_max_tile_level && 180.0 / std::ldexp(1.0, z) > 64.0 * finest)
        ++z;
    return std::min(z, finest_zoom(lattice));
}

int finest_zoom(const GeoLattice &lattice) {
    const double coarsest = std::max(lattice.dlon, lattice.dlat);
    int z = 0;
    while (z < k_max_tile_level && 180.0 / std::ldexp(1.0, z + 1) >= 4.0 * coarsest)
        ++z;
    return z;
}

} // namespace tinlod
