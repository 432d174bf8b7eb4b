#include "common/raytrace/whitted_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include "common/raytrace/ray_offset.h"

namespace hybridlab {

WhittedTracer::WhittedTracer(const RayScene& rays, WhittedSettings settings) : rays_(rays), settings_(settings) {
    for (const Light& l : rays.scene().lights) cones_.push_back(spotCone(l));
}

glm::vec3 WhittedTracer::radiance(const Ray& ray, int depth, float importance, RayStats& stats, RayCone cone,
                                  const MediumStack& media) const {
    SurfaceHit hit;
    const bool found = rays_.intersect(ray, 0.0f, std::numeric_limits<float>::infinity(), hit);
    return radianceFrom(ray, found ? &hit : nullptr, depth, importance, stats, cone, media);
}

glm::vec3 WhittedTracer::radianceFrom(const Ray& ray, const SurfaceHit* hit, int depth, float importance, RayStats& stats, RayCone cone,
                                      const MediumStack& media) const {
    if (!hit) {
        if (media.depth() > 0) ++stats.mediumErrors;  // left the scene inside a closed object: an open mesh
        return skyRadiance(rays_.scene(), ray.direction);
    }
    return radianceAtHit(ray, *hit, depth, importance, stats, cone, media);
}

glm::vec3 WhittedTracer::radianceAtHit(const Ray& ray, const SurfaceHit& hit, int depth, float importance, RayStats& stats,
                                       RayCone cone, const MediumStack& media) const {
    const glm::vec3 L = shade(hit, ray.direction, depth, importance, stats, cone.at(hit.t), media);
    // Beer-Lambert absorption of the media the segment ran through (medium_stack.h).
    return media.absorbs() ? L * segmentTransmittance(media.absorption(), hit.t) : L;
}

namespace {

// The local colour (WhittedTracer::localColor). Forced inline into shadeParts too: called, its
// vec3 arguments and result pass through the stack in halves and reload as pairs, failed
// store-to-load forwardings that cost about 7% of its time.
[[gnu::always_inline]] inline glm::vec3 shadeLocal(const RayScene& rays, const std::vector<SpotCone>& cones, bool traceShadows,
                                                   const SurfaceHit& hit, glm::vec3 normal, glm::vec3 geometricNormal,
                                                   glm::vec3 toViewer, RayStats& stats, float uvLod, glm::vec3 mediumAbsorption) {
    const Scene& scene = rays.scene();
    const SurfacePoint sp{hit.position, normal, hit.uv, hit.material};
    const glm::vec3 tex = diffuseTextureValue(*hit.material, rays.diffuseTexture(*hit.material), hit.uv, uvLod);
    glm::vec3 c = unlitTerm(scene, sp, tex);
    const glm::vec3 shadowOrigin = offsetRayOrigin(hit.position, geometricNormal);
    // A batch of lights' unshadowed terms first, then their shadow rays: the lights' chains of
    // square roots and divisions (sampleLight, blinnPhong) overlap instead of each waiting behind
    // the previous light's ray. The same terms summed in the same order.
    constexpr std::size_t kBatch = 8;
    const std::size_t lights = scene.lights.size();
    for (std::size_t first = 0; first < lights; first += kBatch) {
        const std::size_t count = std::min(kBatch, lights - first);
        LightSample samples[kBatch];
        glm::vec3 direct[kBatch];
        for (std::size_t k = 0; k < count; ++k) {
            samples[k] = sampleLight(scene.lights[first + k], cones[first + k], hit.position);
            direct[k] = blinnPhong(sp, tex, toViewer, samples[k]);
        }
        for (std::size_t k = 0; k < count; ++k) {
            if (direct[k] == glm::vec3(0.0f)) continue;  // facing away, or outside a spot cone: no ray needed
            if (scene.lights[first + k].castsShadows && traceShadows) {
                ++stats.shadow;
                direct[k] *= rays.transmittance(shadowOrigin, samples[k].toLight, samples[k].distance, mediumAbsorption);
            }
            c += direct[k];
        }
    }
    return c;
}

}  // namespace

glm::vec3 WhittedTracer::localColor(const SurfaceHit& hit, glm::vec3 normal, glm::vec3 geometricNormal, glm::vec3 toViewer,
                                    RayStats& stats, bool shadowRays, float uvLod, glm::vec3 mediumAbsorption) const {
    return shadeLocal(rays_, cones_, settings_.shadows && shadowRays, hit, normal, geometricNormal, toViewer, stats, uvLod,
                      mediumAbsorption);
}

glm::vec3 WhittedTracer::shade(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats,
                               RayCone footprint, const MediumStack& media) const {
    return shadeSurface(hit, incoming, depth, importance, stats, {}, footprint, std::nullopt, nullptr, media, LocalColor::IfWeighted)
        .composed(settings_.blend);
}

ShadingParts WhittedTracer::shadeParts(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats,
                                       TracedEffects effects, RayCone footprint, std::optional<glm::vec3> local,
                                       EnvironmentTerms* environment, const MediumStack& media) const {
    return shadeSurface(hit, incoming, depth, importance, stats, effects, footprint, local, environment, media, LocalColor::Always);
}

ShadingParts WhittedTracer::shadeSurface(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats,
                                         TracedEffects effects, RayCone footprint, std::optional<glm::vec3> local,
                                         EnvironmentTerms* environment, const MediumStack& media, LocalColor shadeC) const {
    if (!settings_.rayCones) footprint = {};  // point-sampled textures (texture_filter = "none"), at every depth
    const Material& m = *hit.material;
    const Scene& scene = rays_.scene();
    // Work on the side the ray arrives from.
    const shading_language::ArrivalSide side = shading_language::arrivalSide(incoming, hit.geometricNormal, hit.shadingNormal, m.ior, scene.ambientIor);
    const glm::vec3 ng = side.geometricNormal, n = side.shadingNormal;
    // The composition's weights, the depth limit, the importance cut-off and whether C weighs
    // (common/shading/composition.h).
    const shading_language::HitScattering scattering =
        shading_language::scatterAtHit(incoming, n, side.n1, side.n2, m.reflectivity, m.fresnel, m.opacity, depth, settings_.maxDepth,
                                       settings_.depthLimit == DepthLimit::Local, importance, settings_.importanceCutoff,
                                       effects.reflection, effects.refraction);
    const bool tracesRays = scattering.tracesRays, tir = scattering.tir, traceM = scattering.traceM, traceR = scattering.traceR;
    const float weightM = scattering.weightM, weightR = scattering.weightR;

    ShadingParts parts;
    parts.transparency = scattering.transparency;
    parts.reflectivity = scattering.reflectivity;
    parts.composes = scattering.composes;
    if (local) {
        parts.local = *local;
    } else if (shadeC == LocalColor::Always || scattering.localWeighs) {
        // The footprint's level of detail (a log2) only where a texture reads it.
        const float uvLod = m.diffuseTexture != kNoTexture ? uvFootprintLod(hit.uvDensityLod, footprint, incoming, hit.geometricNormal)
                                                           : -std::numeric_limits<float>::infinity();
        parts.local = shadeLocal(rays_, cones_, settings_.shadows && effects.shadows, hit, n, ng, -incoming, stats, uvLod,
                                 media.absorption());
    }
    if (!tracesRays) return parts;

    const glm::vec3 reflected = scattering.reflectedDirection, refracted = scattering.refractedDirection;
    // The sky only where a term is asked for; a term of weight 0 keeps the local colour.
    EnvironmentTerms sky{parts.local, parts.local};
    if (weightM > 0.0f && (environment || !effects.reflection)) sky.reflected = skyRadiance(scene, reflected);
    if (weightR > 0.0f && (environment || !effects.refraction)) sky.refracted = skyRadiance(scene, refracted);
    if (tir) sky.refracted = sky.reflected;
    if (environment) *environment = sky;

    parts.reflected = parts.refracted = parts.local;
    if (!effects.reflection) {
        parts.reflected = sky.reflected;
    } else if (traceM) {
        ++stats.reflection;
        parts.reflected = radiance({offsetRayOrigin(hit.position, ng), reflected}, depth + 1, importance * weightM, stats, footprint, media);
    }
    if (tir) {
        parts.refracted = parts.reflected;
    } else if (!effects.refraction) {
        parts.refracted = sky.refracted;
    } else if (traceR) {
        ++stats.refraction;
        MediumStack inside = media;
        if (!(side.entering ? inside.enter(hit.object, m.absorption) : inside.leave(hit.object))) ++stats.mediumErrors;
        parts.refracted =
            radiance({offsetRayOrigin(hit.position, -ng), refracted}, depth + 1, importance * weightR, stats, footprint, inside);
    }
    return parts;
}

}  // namespace hybridlab
