// The PROJ backend (backends.hpp): CRS checks and transformations through PROJ's database.
#include "backends.hpp"
#include "tinlod/error.hpp"

#include <proj.h>

namespace tinlod::backends {

namespace {

using Context = std::unique_ptr<PJ_CONTEXT, void (*)(PJ_CONTEXT *)>;
using Object = std::unique_ptr<PJ, void (*)(PJ *)>;

Context make_context() {
    Context ctx(proj_context_create(), [](PJ_CONTEXT *c) { proj_context_destroy(c); });
    proj_log_level(ctx.get(), PJ_LOG_NONE);
    return ctx;
}

Object object(PJ *p) {
    return Object(p, [](PJ *q) { proj_destroy(q); });
}

std::string epsg_code(int epsg) { return "EPSG:" + std::to_string(epsg); }

class Transformation final : public CrsTransformation {
  public:
    Transformation(Context ctx, Object pj) : ctx_(std::move(ctx)), pj_(std::move(pj)) {}
    void apply(std::span<std::array<double, 2>> points) const override {
        if (points.empty())
            return;
        const std::size_t stride = sizeof(points[0]);
        proj_trans_generic(pj_.get(), PJ_FWD, &points[0][0], stride, points.size(), &points[0][1],
                           stride, points.size(), nullptr, 0, 0, nullptr, 0, 0);
    }

  private:
    Context ctx_; // outlives pj_: members are destroyed in reverse order
    Object pj_;
};

class Proj final : public CrsLibrary {
  public:
    void check_crs(const std::string &path, int epsg, bool geographic) override {
        const Context ctx = make_context();
        const std::string code = epsg_code(epsg);
        const Object crs = object(proj_create(ctx.get(), code.c_str()));
        if (!crs)
            throw Error(path, code + " is not a coordinate reference system PROJ knows (or "
                                     "PROJ's database is missing): the raster's units and place "
                                     "are unknown");
        const PJ_TYPE type = proj_get_type(crs.get());
        if (geographic ? type != PJ_TYPE_GEOGRAPHIC_2D_CRS && type != PJ_TYPE_GEOGRAPHIC_3D_CRS
                       : type != PJ_TYPE_PROJECTED_CRS)
            throw Error(path, code + " is not a " + (geographic ? "geographic" : "projected") +
                                  " CRS, yet the file's GeoKeys say it is one");
        if (geographic)
            return;
        const Object cs = object(proj_crs_get_coordinate_system(ctx.get(), crs.get()));
        double to_metres = 0;
        const char *unit = nullptr;
        if (!cs ||
            !proj_cs_get_axis_info(ctx.get(), cs.get(), 0, nullptr, nullptr, nullptr, &to_metres,
                                   &unit, nullptr, nullptr) ||
            to_metres != 1.0)
            throw Error(path, code + " measures in " + (unit ? unit : "unknown units") +
                                  ", not metres: reproject the raster to a metric CRS (gdalwarp)");
    }

    std::unique_ptr<CrsTransformation> transformation(const std::string &path, int from,
                                                      int to) override {
        Context ctx = make_context();
        const std::string src = epsg_code(from), dst = epsg_code(to);
        const Object raw =
            object(proj_create_crs_to_crs(ctx.get(), src.c_str(), dst.c_str(), nullptr));
        // Longitude first, whatever the CRS's axis order.
        Object pj = object(raw ? proj_normalize_for_visualization(ctx.get(), raw.get()) : nullptr);
        if (!pj)
            throw Error(path, "cannot convert " + src + " to " + dst + " (PROJ database missing?)");
        return std::make_unique<Transformation>(std::move(ctx), std::move(pj));
    }
};

} // namespace

extern "C" CrsLibrary *tinlod_proj_backend() {
    static Proj backend;
    return &backend;
}

} // namespace tinlod::backends
