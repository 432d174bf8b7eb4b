#pragma once
// The Embree backend of the Whitted ray tree (common/shading/whitted_tree.h): the class that the
// shared walk's BACKEND_CALLs reach in C++ (shading_language.h), on RayScene and the scene's records.
#include <limits>
#include <vector>

#include "common/raytrace/first_hit_shadows.h"
#include "common/raytrace/medium_stack.h"
#include "common/raytrace/ray_scene.h"
#include "common/raytrace/ray_stats.h"
#include "common/raytrace/shading.h"
#include "common/raytrace/whitted_tracer.h"
#include "common/shading/whitted_tree.h"

namespace hybridlab {

// The Embree backend of the ray tree (common/shading/whitted_tree.h, which walks it for both
// backends): what the walk asks of a backend, on RayScene and the scene's records. WhittedTracer
// walks with it; a hybrid's per-texel shading, written once for Embree and the device, walks with a
// class derived from it that adds what the texel's shared function asks of its backend (reading
// the G-buffer, counting).
class EmbreeTreeBackend {
public:
    using Surface = const SurfaceHit&;

    // `tracer`'s scene and settings, counting into `stats`; ray cones spreading by `coneSpread` (a
    // camera ray's: RayCone::spread).
    EmbreeTreeBackend(const WhittedTracer& tracer, RayStats& stats, float coneSpread)
        : rays_(tracer.rays_), scene_(tracer.rays_.scene()), cones_(tracer.cones_), stats_(stats),
          spread_(tracer.settings_.rayCones ? coneSpread : 0.0f), rayCones_(tracer.settings_.rayCones) {
        const WhittedSettings& settings = tracer.settings_;
        settings_.maxDepth = settings.maxDepth;
        settings_.depthLimitLocal = settings.depthLimit == DepthLimit::Local;
        settings_.importanceCutoff = settings.importanceCutoff;
        settings_.walewski = settings.blend == BlendRule::Walewski2019;
        settings_.shadows = settings.shadows;
        settings_.sceneAmbient = scene_.ambient;
        settings_.ambientIor = scene_.ambientIor;
    }

    EmbreeTreeBackend(const EmbreeTreeBackend&) = delete;  // current_ may point into this object
    EmbreeTreeBackend& operator=(const EmbreeTreeBackend&) = delete;

    // The first traceRay() returns `hit` (null: a miss) instead of tracing: a caller's packet found it.
    void giveFirstHit(const SurfaceHit* hit) {
        given_ = hit ? Given::Hit : Given::Miss;
        if (hit) current_ = hit;
    }

    // The first hit's shadow rays, where a caller's packets traced them (first_hit_shadows.h).
    void giveFirstHitShadows(const FirstHitShadows* shadows) { firstHitShadows_ = shadows; }

    float traceRay(glm::vec3 origin, glm::vec3 direction) {
        if (given_ != Given::None) {
            const bool found = given_ == Given::Hit;
            given_ = Given::None;
            shadowsGiven_ = found ? firstHitShadows_ : nullptr;
            nextShadow_ = 0;
            return found ? current_->t : -1.0f;
        }
        shadowsGiven_ = nullptr;
        current_ = &hit_;
        return rays_.intersect({origin, direction}, 0.0f, std::numeric_limits<float>::infinity(), hit_) ? hit_.t : -1.0f;
    }
    const SurfaceHit& resolveHit() const { return *current_; }

    static shading_language::SurfaceMaterial surfaceMaterial(const SurfaceHit& s) {
        const Material& m = *s.material;
        return {m.emission, m.ambient, m.diffuse, m.specular, m.specularExponent, m.reflectivity, m.ior, m.opacity, m.fresnel};
    }
    glm::vec3 diffuseTexture(const SurfaceHit& s, float coneWidth, glm::vec3 incoming) const {
        const Material& m = *s.material;
        if (m.diffuseTexture == kNoTexture) return glm::vec3(1.0f);
        // The footprint's level of detail (a log2) only where a texture reads it.
        return diffuseTextureValue(m, rays_.diffuseTexture(m), s.uv, shading_language::uvFootprintLod(s.uvDensityLod, coneWidth, incoming, s.geometricNormal));
    }
    int lightCount() const { return static_cast<int>(scene_.lights.size()); }
    LightSample lightSample(int i, glm::vec3 p) const { return sampleLight(scene_.lights[i], cones_[i], p); }
    bool lightCastsShadows(int i) const { return scene_.lights[i].castsShadows; }
    glm::vec3 shadowTransmittance(glm::vec3 origin, glm::vec3 direction, float distance, glm::vec3 startAbsorption) const {
        if (shadowsGiven_)
            if (const glm::vec3* traced = shadowsGiven_->find(origin, direction, distance, startAbsorption, nextShadow_)) return *traced;
        return rays_.transmittance(origin, direction, distance, startAbsorption);
    }
    glm::vec3 skyRadiance(glm::vec3 direction) const { return hybridlab::skyRadiance(scene_, direction); }
    float coneWidthAt(float width, float t) const { return rayCones_ ? width + spread_ * t : 0.0f; }
    const shading_language::TreeSettings& treeSettings() const { return settings_; }
    static MediumEntry mediumEntry(const SurfaceHit& s) { return {s.object, s.material->absorption}; }
    void countRay(int kind) {
        switch (kind) {
        case shading_language::kRayShadow: ++stats_.shadow; break;
        case shading_language::kRayReflection: ++stats_.reflection; break;
        case shading_language::kRayRefraction: ++stats_.refraction; break;
        default: ++stats_.mediumErrors; break;
        }
    }

private:
    enum class Given { None, Hit, Miss };
    const RayScene& rays_;
    const Scene& scene_;
    const std::vector<SpotCone>& cones_;
    RayStats& stats_;
    shading_language::TreeSettings settings_;
    float spread_;
    bool rayCones_;
    Given given_ = Given::None;
    SurfaceHit hit_;
    const SurfaceHit* current_ = &hit_;  // the last traceRay()'s hit: hit_, or the one given
    const FirstHitShadows* firstHitShadows_ = nullptr;  // given for the first hit
    const FirstHitShadows* shadowsGiven_ = nullptr;     // while the first hit is shaded
    mutable int nextShadow_ = 0;                        // where shadowsGiven_'s search goes on
};

}  // namespace hybridlab
