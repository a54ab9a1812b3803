// Coordinate transformations of the tile build, through PROJ (crs.hpp).
#include "crs.hpp"

#include "tinlod/error.hpp"

#include <proj.h>

#include <cmath>

namespace tinlod::tiles {

struct CrsTransform::Impl {
    PJ_CONTEXT *ctx = nullptr;
    PJ *pj = nullptr; // null: the identity
    ~Impl() {
        if (pj)
            proj_destroy(pj);
        if (ctx)
            proj_context_destroy(ctx);
    }
};

CrsTransform::CrsTransform(int from, int to, const std::string &subject)
    : impl_(std::make_unique<Impl>()) {
    if (from == to)
        return;
    impl_->ctx = proj_context_create();
    proj_log_level(impl_->ctx, PJ_LOG_NONE);
    const std::string src = "EPSG:" + std::to_string(from), dst = "EPSG:" + std::to_string(to);
    PJ *raw = proj_create_crs_to_crs(impl_->ctx, src.c_str(), dst.c_str(), nullptr);
    impl_->pj = raw ? proj_normalize_for_visualization(impl_->ctx, raw) : nullptr;
    if (raw)
        proj_destroy(raw);
    if (!impl_->pj)
        throw Error(subject, "PROJ has no transformation from " + src + " to " + dst +
                                 " (PROJ database missing?)");
}

CrsTransform::~CrsTransform() = default;

std::vector<glm::dvec2> CrsTransform::apply(std::span<const glm::dvec2> points) const {
    std::vector<glm::dvec2> out(points.begin(), points.end());
    if (!impl_->pj || out.empty())
        return out;
    proj_trans_generic(impl_->pj, PJ_FWD, &out[0].x, sizeof(glm::dvec2), out.size(), &out[0].y,
                       sizeof(glm::dvec2), out.size(), nullptr, 0, 0, nullptr, 0, 0);
    for (glm::dvec2 &p : out)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || std::abs(p.x) > 1e30)
            p = glm::dvec2(NAN);
    return out;
}

} // namespace tinlod::tiles
