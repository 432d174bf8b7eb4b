#include "common/raytrace/whitted_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include "common/raytrace/embree_tree_backend.h"
#include "common/raytrace/ray_offset.h"

namespace hybridlab {

namespace {

namespace sl = shading_language;

sl::PendingRay pendingRay(const Ray& ray, int depth, float importance, float coneWidth, const MediumStack& media) {
    sl::PendingRay r;
    r.origin = ray.origin;
    r.importance = importance;
    r.direction = ray.direction;
    r.depth = depth;
    r.throughput = glm::vec3(1.0f);
    r.coneWidth = coneWidth;
    r.media = media;
    return r;
}

glm::bvec3 effectsOf(const TracedEffects& e) { return glm::bvec3(e.shadows, e.reflection, e.refraction); }

}  // namespace

WhittedTracer::WhittedTracer(const RayScene& rays, WhittedSettings settings) : rays_(rays), settings_(settings) {
    for (const Light& l : rays.scene().lights) cones_.push_back(spotCone(l));
}

glm::vec3 WhittedTracer::radiance(const Ray& ray, int depth, float importance, RayStats& stats, RayCone cone,
                                  const MediumStack& media) const {
    EmbreeTreeBackend backend(*this, stats, cone.spread);
    return sl::traceTree(backend, pendingRay(ray, depth, importance, cone.width, media), glm::bvec3(true));
}

glm::vec3 WhittedTracer::radianceFrom(const Ray& ray, const SurfaceHit* hit, int depth, float importance, RayStats& stats, RayCone cone,
                                      const MediumStack& media, const FirstHitShadows* shadows) const {
    EmbreeTreeBackend backend(*this, stats, cone.spread);
    backend.giveFirstHit(hit);
    backend.giveFirstHitShadows(shadows);
    return sl::traceTree(backend, pendingRay(ray, depth, importance, cone.width, media), glm::bvec3(true));
}

void WhittedTracer::traceFirstHitShadows(const Ray* rays, const SurfaceHit* hits, const bool* found, int count,
                                         FirstHitShadows* shadows) const {
    if (count < 0 || count > RayScene::kCoherentRays)
        throw std::logic_error("WhittedTracer: first hits come in packets of at most kCoherentRays");
    const Scene& scene = rays_.scene();
    const int lights = std::min(static_cast<int>(scene.lights.size()), FirstHitShadows::kMaxLights);
    glm::vec3 origin[RayScene::kCoherentRays], normal[RayScene::kCoherentRays];
    bool shaded[RayScene::kCoherentRays];
    for (int k = 0; k < count; ++k) {
        shadows[k].count = 0;
        // The local colour is shaded, with shadow rays, unless the composition gives it no weight:
        // a clear surface, or a perfect mirror (composition.h localWeighs; at depth 0 a ray is cut
        // off by nothing). Where it is, on the side the camera ray arrives from (shadeHit()).
        const Material* m = found[k] ? hits[k].material : nullptr;
        shaded[k] = settings_.shadows && m && m->opacity > 0.0f && (m->fresnel || m->reflectivity < 1.0f);
        if (!shaded[k]) continue;
        const sl::ArrivalSide side = sl::arrivalSide(rays[k].direction, hits[k].geometricNormal, hits[k].shadingNormal, m->ior,
                                                     scene.ambientIor);
        origin[k] = sl::shadowRayOrigin(hits[k].position, side.geometricNormal);
        normal[k] = side.shadingNormal;
    }
    for (int i = 0; i < lights; ++i) {
        if (!scene.lights[i].castsShadows) continue;
        // The pixels whose surface faces the light and lies in its cone (hitLocalColor()'s rays).
        ShadowQuery queries[RayScene::kCoherentRays];
        int pixel[RayScene::kCoherentRays], n = 0;
        for (int k = 0; k < count; ++k) {
            if (!shaded[k]) continue;
            const LightSample light = sampleLight(scene.lights[i], cones_[i], hits[k].position);
            if (glm::dot(normal[k], light.toLight) <= 0.0f || light.radiance == glm::vec3(0.0f)) continue;
            queries[n] = {origin[k], light.toLight, light.distance, kAmbientMedium.absorption};
            pixel[n++] = k;
        }
        if (n == 0) continue;
        glm::vec3 transmittance[RayScene::kCoherentRays];
        const ShadowQuery& q = queries[0];
        if (n == 1) transmittance[0] = rays_.transmittance(q.origin, q.direction, q.tmax, q.startAbsorption);
        else rays_.transmittanceCoherent(queries, n, transmittance);
        for (int j = 0; j < n; ++j) {
            FirstHitShadows& s = shadows[pixel[j]];
            s.rays[s.count++] = {queries[j], transmittance[j]};
        }
    }
}

glm::vec3 WhittedTracer::radianceAtHit(const Ray& ray, const SurfaceHit& hit, int depth, float importance, RayStats& stats,
                                       RayCone cone, const MediumStack& media) const {
    return radianceFrom(ray, &hit, depth, importance, stats, cone, media);
}

glm::vec3 WhittedTracer::localColor(const SurfaceHit& hit, glm::vec3 normal, glm::vec3 geometricNormal, glm::vec3 toViewer,
                                    RayStats& stats, bool shadowRays, float uvLod, glm::vec3 mediumAbsorption) const {
    EmbreeTreeBackend backend(*this, stats, 0.0f);
    const glm::vec3 tex = diffuseTextureValue(*hit.material, rays_.diffuseTexture(*hit.material), hit.uv, uvLod);
    return sl::hitLocalColor(backend, hit, EmbreeTreeBackend::surfaceMaterial(hit), normal, geometricNormal, toViewer,
                             settings_.shadows && shadowRays, tex, mediumAbsorption);
}

glm::vec3 WhittedTracer::shade(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats,
                               RayCone footprint, const MediumStack& media) const {
    EmbreeTreeBackend backend(*this, stats, footprint.spread);
    // C shaded only where the composition weighs it: the caller reads the composed radiance alone.
    const sl::HitParts p = sl::shadeParts(backend, hit, EmbreeTreeBackend::surfaceMaterial(hit), incoming, depth, importance,
                                          backend.coneWidthAt(footprint.width, 0.0f), media, glm::bvec3(true), false, glm::vec3(0.0f),
                                          true, false);
    return sl::composedParts(p, settings_.blend == BlendRule::Walewski2019);
}

sl::HitParts WhittedTracer::shadeParts(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats,
                                       TracedEffects effects, RayCone footprint, std::optional<glm::vec3> local,
                                       const MediumStack& media) const {
    EmbreeTreeBackend backend(*this, stats, footprint.spread);
    return sl::shadeParts(backend, hit, EmbreeTreeBackend::surfaceMaterial(hit), incoming, depth, importance,
                          backend.coneWidthAt(footprint.width, 0.0f), media, effectsOf(effects), local.has_value(),
                          local.value_or(glm::vec3(0.0f)), false, false);
}

}  // namespace hybridlab
