// Coordinate transformations of the tile build, through PROJ (crs.hpp).
#include "crs.hpp"

#include "tinlod/error.hpp"

#include <proj.h>

#include <cmath>
#include <memory>

namespace tinlod::tiles {

std::vector<glm::dvec2> transform_points(int from, int to, std::span<const glm::dvec2> points,
                                         const std::string &subject) {
    std::vector<glm::dvec2> out(points.begin(), points.end());
    if (from == to)
        return out;
    const std::unique_ptr<PJ_CONTEXT, void (*)(PJ_CONTEXT *)> ctx(
        proj_context_create(), [](PJ_CONTEXT *c) { proj_context_destroy(c); });
    proj_log_level(ctx.get(), PJ_LOG_NONE);
    const std::string src = "EPSG:" + std::to_string(from), dst = "EPSG:" + std::to_string(to);
    const std::unique_ptr<PJ, void (*)(PJ *)> raw(
        proj_create_crs_to_crs(ctx.get(), src.c_str(), dst.c_str(), nullptr),
        [](PJ *p) { proj_destroy(p); });
    const std::unique_ptr<PJ, void (*)(PJ *)> pj(
        raw ? proj_normalize_for_visualization(ctx.get(), raw.get()) : nullptr,
        [](PJ *p) { proj_destroy(p); });
    if (!pj)
        throw Error(subject, "PROJ has no transformation from " + src + " to " + dst +
                                 " (PROJ database missing?)");
    if (!out.empty())
        proj_trans_generic(pj.get(), PJ_FWD, &out[0].x, sizeof(glm::dvec2), out.size(), &out[0].y,
                           sizeof(glm::dvec2), out.size(), nullptr, 0, 0, nullptr, 0, 0);
    for (glm::dvec2 &p : out)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || std::abs(p.x) > 1e30)
            p = glm::dvec2(NAN);
    return out;
}

} // namespace tinlod::tiles
