// The DEMs of a tile set as one lattice in longitude and latitude (tiles.hpp: load_coverage).
#include "crs.hpp"

#include "tinlod/error.hpp"
#include "tinlod/tiles.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <list>
#include <map>
#include <memory>
#include <mutex>

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

// Where each DEM of one grid stands on the lattice: its first post's column and row.
struct Mosaic {
    std::vector<std::pair<std::int64_t, std::int64_t>> offsets;
};

GeoLattice mosaic_grid(const std::vector<Heightfield> &dems, Mosaic &plan) {
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
    for (const auto &[oi, oj] : offsets)
        plan.offsets.emplace_back(oi - i0, oj - j0);
    return g;
}

// Lattice rows [ja, jb) into `out` (NaN where no DEM is), from DEM k's rows through
// `rows(k, r0, r1)` (its heights, row r0 first). Where DEMs overlap (adjacent SRTM tiles share a
// row or column) the first one given wins.
template <typename Rows>
void mosaic_rows(const std::vector<Heightfield> &dems, const Mosaic &plan, const GeoLattice &g,
                 std::int64_t ja, std::int64_t jb, Rows &&rows, float *out) {
    for (std::size_t k = 0; k < dems.size(); ++k) {
        const Heightfield &d = dems[k];
        const auto [oi, oj] = plan.offsets[k];
        const std::int64_t r0 = std::max<std::int64_t>(0, ja - oj);
        const std::int64_t r1 = std::min<std::int64_t>(d.height, jb - oj);
        if (r1 <= r0)
            continue;
        const float *src = rows(k, int(r0), int(r1));
        for (std::int64_t r = r0; r < r1; ++r)
            for (int c = 0; c < d.width; ++c) {
                float &post =
                    out[std::size_t(r + oj - ja) * std::size_t(g.width) + std::size_t(c + oi)];
                if (std::isnan(post))
                    post = src[std::size_t(r - r0) * std::size_t(d.width) + std::size_t(c)];
            }
    }
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

// The DEMs' footprints and the transformations from the lattice into their CRSs.
struct Warp {
    std::vector<GeoRect> boxes;
    std::vector<std::unique_ptr<crs::Transformation>> to_dem;
};

GeoLattice warp_grid(const std::vector<Heightfield> &dems, const std::vector<std::string> &paths,
                     Warp &plan) {
    std::vector<GeoRect> &boxes = plan.boxes;
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
    for (std::size_t k = 0; k < dems.size(); ++k)
        plan.to_dem.push_back(
            std::make_unique<crs::Transformation>(paths[k], 4326, dems[k].native_epsg));
    return g;
}

// Lattice rows [ja, jb) into `out`: each post takes the bilinear interpolation of the first DEM
// whose samples surround it, read through `rows(k, r0, r1)` (DEM k's heights, row r0 first).
template <typename Rows>
void warp_rows(const std::vector<Heightfield> &dems, const Warp &plan, const GeoLattice &g,
               std::int64_t ja, std::int64_t jb, Rows &&rows, float *out) {
    const std::int64_t w = g.width, h = g.height;
    for (std::size_t k = 0; k < dems.size(); ++k) {
        const Heightfield &d = dems[k];
        const GeoRect &box = plan.boxes[k];
        const auto i0 =
            std::max<std::int64_t>(0, std::int64_t(std::floor((box.west - g.lon0) / g.dlon)));
        const auto i1 =
            std::min<std::int64_t>(w - 1, std::int64_t(std::ceil((box.east - g.lon0) / g.dlon)));
        const auto j0 = std::max<std::int64_t>(
            ja, std::max<std::int64_t>(0, std::int64_t(std::floor((box.south - g.lat0) / g.dlat))));
        const auto j1 = std::min<std::int64_t>(
            jb - 1,
            std::min<std::int64_t>(h - 1, std::int64_t(std::ceil((box.north - g.lat0) / g.dlat))));
        if (j1 < j0 || i1 < i0)
            continue;
        // Where each post falls among the DEM's samples (NaN: outside it), then the DEM's rows
        // those places need, read at once.
        std::vector<glm::dvec2> row, places;
        for (std::int64_t j = j0; j <= j1; ++j) {
            row.clear();
            for (std::int64_t i = i0; i <= i1; ++i)
                row.emplace_back(g.lon(i), g.lat(j));
            for (const glm::dvec2 &p : plan.to_dem[k]->apply(row)) {
                double c = (p.x - d.native_x0) / d.native_dx, r = (p.y - d.native_y0) / d.native_dy;
                // A post within float noise of the DEM's outline is on it.
                if (std::abs(c - std::round(c)) <= k_same_grid)
                    c = std::round(c);
                if (std::abs(r - std::round(r)) <= k_same_grid)
                    r = std::round(r);
                if (std::isnan(p.x) || c < 0 || r < 0 || c > d.width - 1 || r > d.height - 1)
                    places.emplace_back(NAN, NAN);
                else
                    places.emplace_back(c, r);
            }
        }
        int r_lo = d.height, r_hi = -1;
        for (const glm::dvec2 &p : places)
            if (!std::isnan(p.x)) {
                const int r0 = std::min(int(p.y), d.height - 2);
                r_lo = std::min(r_lo, r0), r_hi = std::max(r_hi, r0 + 1);
            }
        if (r_hi < 0)
            continue;
        const float *src = rows(k, r_lo, r_hi + 1);
        const auto at = [&](int c, int r) {
            return src[std::size_t(r - r_lo) * std::size_t(d.width) + std::size_t(c)];
        };
        std::size_t n = 0;
        for (std::int64_t j = j0; j <= j1; ++j)
            for (std::int64_t i = i0; i <= i1; ++i, ++n) {
                float &post = out[std::size_t(j - ja) * std::size_t(w) + std::size_t(i)];
                const double c = places[n].x, r = places[n].y;
                if (!std::isnan(post) || std::isnan(c))
                    continue;
                const int c0 = std::min(int(c), d.width - 2), r0 = std::min(int(r), d.height - 2);
                const double tc = c - c0, tr = r - r0;
                const double south = (1 - tc) * at(c0, r0) + tc * at(c0 + 1, r0);
                const double north = (1 - tc) * at(c0, r0 + 1) + tc * at(c0 + 1, r0 + 1);
                post = float((1 - tr) * south + tr * north);
            }
    }
}

// The lattice's checks once its posts are known: within the tiling scheme, and holding a height.
void check_lattice(const GeoLattice &g, const std::vector<std::string> &paths) {
    // Longitudes run -180..180 in the tiling scheme (a file in 0..360 is not moved).
    constexpr double k_slack = 1e-9;
    if (g.lon(0) < -180.0 - k_slack || g.lon(g.width - 1) > 180.0 + k_slack ||
        g.lat(0) < -90.0 - k_slack || g.lat(g.height - 1) > 90.0 + k_slack)
        throw Error(paths[0], "the DEMs reach beyond longitudes -180..180 or latitudes -90..90");
}

void check_covered(const GeoLattice &g, const std::vector<std::string> &paths) {
    if (g.covered == 0)
        throw Error(paths[0], "no lattice post falls inside the DEMs");
}

void check_dem(const Heightfield &d, const std::string &path) {
    if (d.native_epsg == 0)
        throw Error(path, "has no georeferencing with an EPSG code: where its tiles lie on "
                          "Earth is unknown");
    if (d.width < 2 || d.height < 2)
        throw Error(path, "needs at least 2 x 2 samples");
}

GeoLattice whole_coverage(const std::vector<std::string> &paths, const LoadOptions &options) {
    std::vector<Heightfield> dems;
    for (const std::string &path : paths) {
        dems.push_back(load_heightfield(path, options));
        check_dem(dems.back(), path);
    }
    const auto rows = [&dems](std::size_t k, int r0, int) {
        return dems[k].z.data() + std::size_t(r0) * std::size_t(dems[k].width);
    };
    GeoLattice g;
    if (on_one_grid(dems)) {
        Mosaic plan;
        g = mosaic_grid(dems, plan);
        g.z.assign(std::size_t(g.width) * std::size_t(g.height), NAN);
        mosaic_rows(dems, plan, g, 0, g.height, rows, g.z.data());
    } else {
        Warp plan;
        g = warp_grid(dems, paths, plan);
        g.z.assign(std::size_t(g.width) * std::size_t(g.height), NAN);
        warp_rows(dems, plan, g, 0, g.height, rows, g.z.data());
    }
    check_lattice(g, paths);
    for (const float h : g.z)
        g.covered += std::isnan(h) ? 0 : 1;
    check_covered(g, paths);
    return g;
}

constexpr double k_mib = 1024.0 * 1024.0;
// What a run holds besides the lattice, MiB: the program and its libraries, and per tile built
// at once that tile's work (an interior of up to 1,024 x 1,024 posts, greedy insertion's TIN and
// the node erase over it, the measure's marks, the encoded tile: up to 150 MiB measured on a
// coarse level's tile).
constexpr double k_fixed_mb = 48.0;
constexpr double k_per_thread_mb = 160.0;
// Bytes a whole load holds per DEM sample at its peak (load_heightfield's estimate for one float
// channel), beside the lattice's 4 per post.
constexpr double k_load_bytes_per_sample = 20.0;
// Posts in a band, at most, and bands the cache holds, at least.
constexpr std::int64_t k_band_posts = std::int64_t(1) << 20;
constexpr std::size_t k_min_bands = 4;

} // namespace

// A band's heights in a mapping of their own, returned to the system when the band goes: made in
// malloc's arenas, bands made by one thread and evicted by another kept every arena resident
// (1.1 GiB for a cache of 336 MiB).
class BandData {
  public:
    explicit BandData(const std::vector<float> &z) : size_(z.size()) {
        void *p = mmap(nullptr, bytes(), PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
        if (p == MAP_FAILED)
            throw std::bad_alloc();
        data_ = static_cast<float *>(p);
        std::copy(z.begin(), z.end(), data_);
    }
    ~BandData() { munmap(data_, bytes()); }
    BandData(const BandData &) = delete;
    BandData &operator=(const BandData &) = delete;
    float operator[](std::size_t k) const { return data_[k]; }
    std::size_t bytes() const { return std::max<std::size_t>(1, size_ * sizeof(float)); }

  private:
    std::size_t size_;
    float *data_ = nullptr;
};

// A band is `rows` lattice rows, all columns; the cache keeps the most recently used bands within
// its budget. A band is read under the lock (the DEMs' readers read one window at a time); the
// threads that read a band keep it while they read it, evicted or not.
class LatticeBands {
  public:
    using Load = std::function<std::vector<float>(std::int64_t j0, std::int64_t j1)>;
    LatticeBands(int width, int height, int rows, std::size_t budget, Load load)
        : width_(width), height_(height), rows_(rows), budget_(budget), load_(std::move(load)),
          id_(next_id()) {}

    int rows() const { return rows_; }
    std::int64_t reads() const { return reads_; }
    std::int64_t count() const { return (height_ + rows_ - 1) / rows_; }

    float post(std::int64_t i, std::int64_t j) {
        // The band each thread read last, checked without the lock.
        thread_local std::uint64_t owner = 0;
        thread_local std::int64_t band = -1;
        thread_local std::shared_ptr<const BandData> data;
        const std::int64_t b = j / rows_;
        if (owner != id_ || band != b) {
            data = fetch(b);
            owner = id_, band = b;
        }
        return (*data)[std::size_t(j - b * rows_) * std::size_t(width_) + std::size_t(i)];
    }

  private:
    static std::uint64_t next_id() {
        static std::atomic<std::uint64_t> ids{0};
        return ++ids;
    }

    std::shared_ptr<const BandData> fetch(std::int64_t b) {
        const std::lock_guard<std::mutex> guard(lock_);
        if (const auto it = index_.find(b); it != index_.end()) {
            used_.splice(used_.begin(), used_, it->second);
            return it->second->second;
        }
        ++reads_;
        auto data = std::make_shared<const BandData>(
            load_(b * rows_, std::min<std::int64_t>(height_, (b + 1) * rows_)));
        used_.emplace_front(b, data);
        index_[b] = used_.begin();
        held_ += data->bytes();
        while (held_ > budget_ && used_.size() > 1) {
            held_ -= used_.back().second->bytes();
            index_.erase(used_.back().first);
            used_.pop_back();
        }
        return data;
    }

    int width_, height_, rows_;
    std::size_t budget_, held_ = 0;
    std::atomic<std::int64_t> reads_{0};
    Load load_;
    std::uint64_t id_;
    std::mutex lock_;
    std::list<std::pair<std::int64_t, std::shared_ptr<const BandData>>> used_;
    std::map<std::int64_t, decltype(used_)::iterator> index_;
};

float GeoLattice::band_post(std::int64_t i, std::int64_t j) const { return bands->post(i, j); }

int GeoLattice::rows_together() const { return bands ? bands->rows() : std::max(height, 1); }

std::int64_t GeoLattice::bands_read() const { return bands ? bands->reads() : 0; }

std::int64_t GeoLattice::band_count() const { return bands ? bands->count() : 1; }

double default_memory_mb() {
    // Half of it: the rest is the system's and other programs'.
    return 0.5 * double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)) / k_mib;
}

GeoLattice load_coverage(const std::vector<std::string> &paths, const LoadOptions &options,
                         const CoverageMemory &memory) {
    const double work_mb = k_fixed_mb + double(std::max(1, memory.threads)) * k_per_thread_mb;
    if (memory.memory_mb <= 0)
        return whole_coverage(paths, options);
    std::int64_t samples = 0, largest = 0;
    try {
        for (const std::string &path : paths) {
            const std::int64_t n = raster_samples(path);
            samples += n, largest = std::max(largest, n);
        }
    } catch (const Error &) {
        return whole_coverage(paths, options); // which names the file at fault as always
    }
    if ((4.0 * double(samples) + k_load_bytes_per_sample * double(largest)) / k_mib + work_mb <=
        memory.memory_mb)
        return whole_coverage(paths, options);

    // By windows: the DEMs' catalogue, then the lattice's bands as the tiles read them.
    auto windows = std::make_shared<std::vector<std::unique_ptr<DemWindows>>>();
    std::vector<Heightfield> dems;
    for (const std::string &path : paths) {
        windows->push_back(std::make_unique<DemWindows>(path, options));
        dems.push_back(windows->back()->grid());
        check_dem(dems.back(), path);
    }
    // DEM k's rows [r0, r1), each band's read kept while the band is made.
    auto rows = [windows, held = std::make_shared<std::vector<float>>()](std::size_t k, int r0,
                                                                         int r1) {
        *held = (*windows)[k]->rows(r0, r1);
        return held->data();
    };
    GeoLattice g;
    LatticeBands::Load load;
    if (on_one_grid(dems)) {
        auto plan = std::make_shared<Mosaic>();
        g = mosaic_grid(dems, *plan);
        load = [dems, plan, g, rows](std::int64_t j0, std::int64_t j1) {
            std::vector<float> out(std::size_t(j1 - j0) * std::size_t(g.width), NAN);
            mosaic_rows(dems, *plan, g, j0, j1, rows, out.data());
            return out;
        };
    } else {
        auto plan = std::make_shared<Warp>();
        g = warp_grid(dems, paths, *plan);
        load = [dems, plan, g, rows](std::int64_t j0, std::int64_t j1) {
            std::vector<float> out(std::size_t(j1 - j0) * std::size_t(g.width), NAN);
            warp_rows(dems, *plan, g, j0, j1, rows, out.data());
            return out;
        };
    }
    check_lattice(g, paths);
    // The cache takes what the run's work leaves, and holds a few bands (of 16 rows at least)
    // however little that is.
    const double cache_mb = std::max(0.0, memory.memory_mb - work_mb);
    const std::int64_t band_bytes =
        std::min<std::int64_t>(k_band_posts * 4, std::int64_t(cache_mb * k_mib / k_min_bands));
    const int rows_per_band = int(std::clamp<std::int64_t>(band_bytes / (4 * std::int64_t(g.width)),
                                                           std::min(16, g.height), g.height));
    const auto budget =
        std::max(std::size_t(cache_mb * k_mib),
                 k_min_bands * std::size_t(rows_per_band) * std::size_t(g.width) * sizeof(float));
    g.bands =
        std::make_shared<LatticeBands>(g.width, g.height, rows_per_band, budget, std::move(load));
    for (std::int64_t j = 0; j < g.height; ++j)
        for (std::int64_t i = 0; i < g.width; ++i)
            g.covered += std::isnan(g.at(i, j)) ? 0 : 1;
    check_covered(g, paths);
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
