#pragma once
// A frame's ray counts as FrameResult counters, under the same names for every technique.
#include "common/raytrace/ray_stats.h"
#include "techniques/technique.h"

namespace hybridlab {

inline void recordRayCounters(const RayStats& rays, double pixelsRayTraced, FrameResult& result) {
    result.counters["rays_primary"] = static_cast<double>(rays.primary);
    result.counters["rays_shadow"] = static_cast<double>(rays.shadow);
    result.counters["rays_reflection"] = static_cast<double>(rays.reflection);
    result.counters["rays_refraction"] = static_cast<double>(rays.refraction);
    result.counters["rays_total"] = static_cast<double>(rays.total());
    result.counters["pixels_ray_traced"] = pixelsRayTraced;
    result.counters["medium_errors"] = static_cast<double>(rays.mediumErrors);
}

}  // namespace hybridlab
