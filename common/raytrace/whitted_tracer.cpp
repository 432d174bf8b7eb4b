#include "common/raytrace/whitted_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include "common/raytrace/ray_offset.h"
#include "common/shading/whitted_tree.h"

namespace hybridlab {

namespace {

namespace sl = shading_language;

// The Embree backend of the ray tree (common/shading/whitted_tree.h, which walks it for both
// backends): what the walk asks of a backend, on RayScene and the scene's records.
class EmbreeTreeBackend {
public:
    using Surface = const SurfaceHit&;

    EmbreeTreeBackend(const RayScene& rays, const std::vector<SpotCone>& cones, const WhittedSettings& settings, RayStats& stats,
                      float coneSpread)
        : rays_(rays), scene_(rays.scene()), cones_(cones), stats_(stats), spread_(settings.rayCones ? coneSpread : 0.0f),
          rayCones_(settings.rayCones) {
        settings_.maxDepth = settings.maxDepth;
        settings_.depthLimitLocal = settings.depthLimit == DepthLimit::Local;
        settings_.importanceCutoff = settings.importanceCutoff;
        settings_.walewski = settings.blend == BlendRule::Walewski2019;
        settings_.shadows = settings.shadows;
        settings_.sceneAmbient = scene_.ambient;
        settings_.ambientIor = scene_.ambientIor;
    }

    // The first traceRay() returns `hit` (null: a miss) instead of tracing: a caller's packet found it.
    void giveFirstHit(const SurfaceHit* hit) {
        given_ = hit ? Given::Hit : Given::Miss;
        if (hit) current_ = hit;
    }

    float traceRay(glm::vec3 origin, glm::vec3 direction) {
        if (given_ != Given::None) {
            const bool found = given_ == Given::Hit;
            given_ = Given::None;
            return found ? current_->t : -1.0f;
        }
        current_ = &hit_;
        return rays_.intersect({origin, direction}, 0.0f, std::numeric_limits<float>::infinity(), hit_) ? hit_.t : -1.0f;
    }
    const SurfaceHit& resolveHit() const { return *current_; }

    static sl::SurfaceMaterial surfaceMaterial(const SurfaceHit& s) {
        const Material& m = *s.material;
        return {m.emission, m.ambient, m.diffuse, m.specular, m.specularExponent, m.reflectivity, m.ior, m.opacity, m.fresnel};
    }
    glm::vec3 diffuseTexture(const SurfaceHit& s, float coneWidth, glm::vec3 incoming) const {
        const Material& m = *s.material;
        if (m.diffuseTexture == kNoTexture) return glm::vec3(1.0f);
        // The footprint's level of detail (a log2) only where a texture reads it.
        return diffuseTextureValue(m, rays_.diffuseTexture(m), s.uv, sl::uvFootprintLod(s.uvDensityLod, coneWidth, incoming, s.geometricNormal));
    }
    int lightCount() const { return static_cast<int>(scene_.lights.size()); }
    LightSample lightSample(int i, glm::vec3 p) const { return sampleLight(scene_.lights[i], cones_[i], p); }
    bool lightCastsShadows(int i) const { return scene_.lights[i].castsShadows; }
    glm::vec3 shadowTransmittance(glm::vec3 origin, glm::vec3 direction, float distance, glm::vec3 startAbsorption) const {
        return rays_.transmittance(origin, direction, distance, startAbsorption);
    }
    glm::vec3 skyRadiance(glm::vec3 direction) const { return hybridlab::skyRadiance(scene_, direction); }
    float coneWidthAt(float width, float t) const { return rayCones_ ? width + spread_ * t : 0.0f; }
    const sl::TreeSettings& treeSettings() const { return settings_; }
    static MediumEntry mediumEntry(const SurfaceHit& s) { return {s.object, s.material->absorption}; }
    void countRay(int kind) {
        switch (kind) {
        case sl::kRayShadow: ++stats_.shadow; break;
        case sl::kRayReflection: ++stats_.reflection; break;
        case sl::kRayRefraction: ++stats_.refraction; break;
        default: ++stats_.mediumErrors; break;
        }
    }

private:
    enum class Given { None, Hit, Miss };
    const RayScene& rays_;
    const Scene& scene_;
    const std::vector<SpotCone>& cones_;
    RayStats& stats_;
    sl::TreeSettings settings_;
    float spread_;
    bool rayCones_;
    Given given_ = Given::None;
    SurfaceHit hit_;
    const SurfaceHit* current_ = &hit_;  // the last traceRay()'s hit: hit_, or the one given
};

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
    EmbreeTreeBackend backend(rays_, cones_, settings_, stats, cone.spread);
    return sl::traceTree(backend, pendingRay(ray, depth, importance, cone.width, media), glm::bvec3(true));
}

glm::vec3 WhittedTracer::radianceFrom(const Ray& ray, const SurfaceHit* hit, int depth, float importance, RayStats& stats, RayCone cone,
                                      const MediumStack& media) const {
    EmbreeTreeBackend backend(rays_, cones_, settings_, stats, cone.spread);
    backend.giveFirstHit(hit);
    return sl::traceTree(backend, pendingRay(ray, depth, importance, cone.width, media), glm::bvec3(true));
}

glm::vec3 WhittedTracer::radianceAtHit(const Ray& ray, const SurfaceHit& hit, int depth, float importance, RayStats& stats,
                                       RayCone cone, const MediumStack& media) const {
    return radianceFrom(ray, &hit, depth, importance, stats, cone, media);
}

glm::vec3 WhittedTracer::localColor(const SurfaceHit& hit, glm::vec3 normal, glm::vec3 geometricNormal, glm::vec3 toViewer,
                                    RayStats& stats, bool shadowRays, float uvLod, glm::vec3 mediumAbsorption) const {
    EmbreeTreeBackend backend(rays_, cones_, settings_, stats, 0.0f);
    const glm::vec3 tex = diffuseTextureValue(*hit.material, rays_.diffuseTexture(*hit.material), hit.uv, uvLod);
    return sl::hitLocalColor(backend, hit, EmbreeTreeBackend::surfaceMaterial(hit), normal, geometricNormal, toViewer,
                             settings_.shadows && shadowRays, tex, mediumAbsorption);
}

namespace {

// shading_language::shadeParts()'s terms as ShadingParts, and its environment terms where the hit
// would trace rays (at a hit that composes, above the depth limit).
ShadingParts shadingParts(const sl::HitParts& p, bool tracesRays, EnvironmentTerms* environment) {
    ShadingParts parts;
    parts.local = p.local;
    parts.reflected = p.reflected;
    parts.refracted = p.refracted;
    parts.reflectivity = p.reflectivity;
    parts.transparency = p.transparency;
    parts.composes = p.composes;
    if (environment && p.composes && tracesRays) *environment = {p.skyReflected, p.skyRefracted};
    return parts;
}

}  // namespace

glm::vec3 WhittedTracer::shade(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats,
                               RayCone footprint, const MediumStack& media) const {
    EmbreeTreeBackend backend(rays_, cones_, settings_, stats, footprint.spread);
    // C shaded only where the composition weighs it: the caller reads the composed radiance alone.
    const sl::HitParts p = sl::shadeParts(backend, hit, EmbreeTreeBackend::surfaceMaterial(hit), incoming, depth, importance,
                                          backend.coneWidthAt(footprint.width, 0.0f), media, glm::bvec3(true), false, glm::vec3(0.0f),
                                          true, false);
    return sl::composedParts(p, settings_.blend == BlendRule::Walewski2019);
}

ShadingParts WhittedTracer::shadeParts(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats,
                                       TracedEffects effects, RayCone footprint, std::optional<glm::vec3> local,
                                       EnvironmentTerms* environment, const MediumStack& media) const {
    EmbreeTreeBackend backend(rays_, cones_, settings_, stats, footprint.spread);
    return shadingParts(sl::shadeParts(backend, hit, EmbreeTreeBackend::surfaceMaterial(hit), incoming, depth, importance,
                                       backend.coneWidthAt(footprint.width, 0.0f), media, effectsOf(effects), local.has_value(),
                                       local.value_or(glm::vec3(0.0f)), false, environment != nullptr),
                        depth < settings_.maxDepth, environment);
}

}  // namespace hybridlab
