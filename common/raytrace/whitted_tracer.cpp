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
    const bool entering = glm::dot(incoming, hit.geometricNormal) < 0.0f;
    const glm::vec3 ng = entering ? hit.geometricNormal : -hit.geometricNormal;
    glm::vec3 n = entering ? hit.shadingNormal : -hit.shadingNormal;

    ShadingParts parts;
    parts.transparency = 1.0f - m.opacity;
    const float orr = parts.transparency;
    const float n1 = entering ? scene.ambientIor : m.ior, n2 = entering ? m.ior : scene.ambientIor;
    const float cosi = std::max(-glm::dot(incoming, n), 0.0f);
    const float om = m.fresnel ? fresnelDielectric(cosi, n1, n2) : m.reflectivity;
    parts.reflectivity = om;
    // C alone where the surface neither reflects nor refracts, or at the depth limit with "local";
    // at the limit with "weighted" the rays not traced count 0 (under total internal reflection too).
    parts.composes = (om > 0.0f || orr > 0.0f) && !(depth >= settings_.maxDepth && settings_.depthLimit == DepthLimit::Local);
    const bool tracesRays = parts.composes && depth < settings_.maxDepth;
    glm::vec3 refracted;
    const bool tir = tracesRays && orr > 0.0f && !refractDirection(incoming, n, n1 / n2, refracted);
    // Total internal reflection sends everything to the reflected ray.
    const float weightM = tir ? om + (1.0f - om) * orr : om;
    const float weightR = tir ? 0.0f : (1.0f - om) * orr;
    auto worthTracing = [&](float w) { return w > 0.0f && importance * w >= settings_.importanceCutoff; };
    const bool traceM = tracesRays && effects.reflection && worthTracing(weightM);
    const bool traceR = tracesRays && !tir && effects.refraction && worthTracing(weightR);

    // C weighs (1 - o_m)(1 - o_r) in the composition under both rules. It also stands in for a ray
    // not traced (the importance cut-off): the reflected one, weighted by weightM (which the
    // refracted one copies under total internal reflection), or the refracted one, whose weight
    // carries the factor o_r under both rules. Where none of these weighs (clear glass, total
    // internal reflection, a perfect mirror, each with its rays traced), the composed radiance does
    // not depend on C: its shading and shadow rays are skipped, C = 0 leaving the sum bit for bit
    // the same.
    const bool localWeighs = !parts.composes || (om < 1.0f && orr < 1.0f) ||
                             (tracesRays && ((!traceM && weightM > 0.0f) || (!tir && !traceR && orr > 0.0f)));
    if (local) {
        parts.local = *local;
    } else if (shadeC == LocalColor::Always || localWeighs) {
        // The footprint's level of detail (a log2) only where a texture reads it.
        const float uvLod = m.diffuseTexture != kNoTexture ? uvFootprintLod(hit.uvDensityLod, footprint, incoming, hit.geometricNormal)
                                                           : -std::numeric_limits<float>::infinity();
        parts.local = shadeLocal(rays_, cones_, settings_.shadows && effects.shadows, hit, n, ng, -incoming, stats, uvLod,
                                 media.absorption());
    }
    if (!tracesRays) return parts;

    const glm::vec3 reflected = reflectDirection(incoming, n);
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
        if (!(entering ? inside.enter(hit.object, m.absorption) : inside.leave(hit.object))) ++stats.mediumErrors;
        parts.refracted =
            radiance({offsetRayOrigin(hit.position, -ng), refracted}, depth + 1, importance * weightR, stats, footprint, inside);
    }
    return parts;
}

}  // namespace hybridlab
