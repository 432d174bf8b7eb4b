#include "techniques/shared/two_term_tracer.h"

#include <limits>

#include "common/raytrace/ray_offset.h"
#include "common/raytrace/shading.h"

namespace hybridlab {

TwoTermTracer::TwoTermTracer(const Scene& scene)
    : scene_(scene), systemOfObject_(scene.objects.size(), -1) {
    for (const LensSystemInfo& info : findLensSystems(scene)) {
        for (std::uint32_t o : info.objects) systemOfObject_[o] = static_cast<int>(systems_.size());
        systems_.push_back(std::make_unique<LensSystem>(scene, info));
    }
}

glm::vec3 TwoTermTracer::environmentRadiance(const WhittedTracer& tracer, const LensSystem& system, Ray ray, RayStats& stats) const {
    constexpr int kMaxSteps = 32;  // back faces passed through (outgoing_records.h continues the same way)
    for (int step = 0; step < kMaxSteps; ++step) {
        SurfaceHit hit;
        ++stats.reflection;
        if (!system.environmentRays().intersect(ray, 0.0f, std::numeric_limits<float>::infinity(), hit)) break;
        if (glm::dot(ray.direction, hit.geometricNormal) < 0.0f) return tracer.shade(hit, ray.direction, 1, 1.0f, stats);
        ray.origin = offsetRayOrigin(hit.position, hit.geometricNormal);
    }
    return skyRadiance(scene_, ray.direction);
}

glm::vec3 TwoTermTracer::radiance(const WhittedTracer& tracer, const RayScene& rays, const Ray& ray, RayStats& stats, RayCone cone,
                                  bool* lensPixel) const {
    SurfaceHit first;
    if (!rays.intersect(ray, 0.0f, std::numeric_limits<float>::infinity(), first)) return skyRadiance(rays.scene(), ray.direction);
    const int system = systemOfObject_[first.object];
    if (system < 0) return tracer.radianceAtHit(ray, first, 0, 1.0f, stats, cone);
    const LensSystem& lens = *systems_[static_cast<std::size_t>(system)];
    LensRayCounter counter;
    TwoTermPaths paths;
    const bool hit = traceTwoTermPaths(lens.lensRays(), ray, paths_, counter, paths);
    stats.refraction += counter.queries;
    stats.mediumErrors += counter.mediumErrors;
    if (!hit) return tracer.radianceAtHit(ray, first, 0, 1.0f, stats, cone);
    if (lensPixel) *lensPixel = true;
    glm::vec3 sum(0.0f);
    for (const LensPath& p : paths.terms) {
        if (!p.exists || p.fresnel <= 0.0f) continue;
        sum += p.weight() * environmentRadiance(tracer, lens, Ray{p.exitOrigin, p.exitDirection}, stats);
    }
    return sum;
}

}  // namespace hybridlab
