#pragma once
// Whitted ray tracing (Whitted 1980; Walewski 2019 Listing 8c with the composition rule of
// DESIGN.md) on Embree: hard shadows from every light, reflection and refraction to a depth limit,
// the local colour at the limit, the sky on a miss. The tree's walk, what a hit shades and which
// rays it spawns are common/shading/whitted_tree.h, written once for this backend and the
// device's (device_whitted_tree.glsl); embree_tree_backend.h gives it RayScene's rays. The reference
// technique calls it from camera rays; hybrid techniques call shadeParts() from a G-buffer texel.
#include <optional>
#include <vector>

#include "common/raytrace/first_hit_shadows.h"
#include "common/raytrace/medium_stack.h"
#include "common/raytrace/ray_cone.h"
#include "common/raytrace/ray_scene.h"
#include "common/raytrace/ray_stats.h"
#include "common/raytrace/shading.h"
#include "common/shading/whitted_tree_types.h"

namespace hybridlab {

// What a hit at the depth limit returns. Weighted: its local colour C weighted as the composition
// weights it, (1 - o_m)(1 - o_r) C, the reflected and refracted rays it would trace counting 0: the
// ray tree truncated at the limit, the sum over every path up to it. Raising the limit only adds
// paths, so the image converges from below, and the error is the weight of the paths cut off;
// POV-Ray does the same (black past max_trace_level), so the two agree exactly. Local: C with
// weight 1, standing in for everything beyond (what the reference did first): an estimate that
// assumes the rest looks like the surface, neither a bound nor convergent (a mirror's dull local
// colour counts fully). Weighted is the default for that reason.
enum class DepthLimit { Weighted, Local };

struct WhittedSettings {
    int maxDepth = 10;             // secondary bounces; a hit at this depth returns what depthLimit says
    DepthLimit depthLimit = DepthLimit::Weighted;
    float importanceCutoff = 0.0f; // a secondary ray whose weight in the pixel falls below this is not
                                   // traced and the surface's local colour stands in, as at the depth
                                   // limit (0: the full ray tree)
    BlendRule blend = BlendRule::Design;
    bool shadows = true;           // shadow rays; off: every light unshadowed (to compare with raster without shadows)
    bool rayCones = true;          // filter textures over ray cones' footprints (ray_cone.h), as the rasterizer's
                                   // mip-mapping; off: point lookups (bilinear at level 0), as POV-Ray's image maps
};

// Which of a surface's effects are ray traced. An effect not traced takes what the rasterizer puts
// in its place (common/raster/shaders/deferred_lighting.frag): no shadow rays, and the sky in the
// reflected and refracted directions (environment mapping). Hybrid techniques trace some effects of
// some objects (Walewski 2019 §3.3; per-effect selection, §6's future work).
struct TracedEffects {
    bool shadows = true;
    bool reflection = true;
    bool refraction = true;
};

class EmbreeTreeBackend;

class WhittedTracer {
public:
    WhittedTracer(const RayScene& rays, WhittedSettings settings);

    const WhittedSettings& settings() const { return settings_; }

    // Radiance arriving along `ray` whose hit would be at recursion depth `depth` (camera rays: 0).
    // `importance` is the ray's weight in the pixel; `cone` its footprint (pixelCone() for camera
    // rays), which filters textures (none: level 0's bilinear lookup); `media` the media it travels
    // in (medium_stack.h; camera rays: none), which absorb along it up to its hit.
    glm::vec3 radiance(const Ray& ray, int depth, float importance, RayStats& stats, RayCone cone = {},
                       const MediumStack& media = kAmbientMedium) const;
    // radiance() for a ray whose first hit the caller has already found: `hit`, or none (null);
    // with `shadows`, the shadow rays of that hit that traceFirstHitShadows() traced.
    glm::vec3 radianceFrom(const Ray& ray, const SurfaceHit* hit, int depth, float importance, RayStats& stats, RayCone cone = {},
                           const MediumStack& media = kAmbientMedium, const FirstHitShadows* shadows = nullptr) const;
    // The shadow rays that camera rays' first hits will trace (rays[k] hit hits[k] where found[k]),
    // traced light by light as coherent packets into shadows[k], for radianceFrom(). A ray that
    // the walk may not ask for is traced too (a light the surface faces, where the local colour
    // is shaded), but not counted: the walk counts what it uses.
    void traceFirstHitShadows(const Ray* rays, const SurfaceHit* hits, const bool* found, int count, FirstHitShadows* shadows) const;
    // radiance() for a ray whose first hit the caller has already found.
    glm::vec3 radianceAtHit(const Ray& ray, const SurfaceHit& hit, int depth, float importance, RayStats& stats, RayCone cone = {},
                            const MediumStack& media = kAmbientMedium) const;

    // Full Whitted shading of a surface hit seen along unit direction `incoming` (towards the
    // surface): local colour with ray-traced shadows, composed with recursive reflection and
    // refraction. The local colour is not shaded where the composition gives it no weight (clear
    // glass, a perfect mirror, total internal reflection): the same radiance, fewer shadow rays.
    // `footprint` is the ray's cone at the hit; `media` those the incoming ray travelled in (the
    // refracted ray enters or leaves the hit object's).
    glm::vec3 shade(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats, RayCone footprint = {},
                    const MediumStack& media = kAmbientMedium) const;

    // shade()'s terms before composition (shading_language::composedParts composes them), tracing
    // only `effects` at this surface (deeper hits trace everything), so that a hybrid technique can
    // substitute or blend its own. `local`: the surface's local colour C when the caller already has
    // it (a hybrid's lit G-buffer texel, shadowed by the shadow maps), taken as is rather than shaded
    // again; unset, it is shaded here (with shadow rays when effects.shadows). An effect not traced
    // takes the sky in its direction, as the rasterizer's environment mapping does.
    shading_language::HitParts shadeParts(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats,
                                          TracedEffects effects = {}, RayCone footprint = {}, std::optional<glm::vec3> local = std::nullopt,
                                          const MediumStack& media = kAmbientMedium) const;

    // The local colour C (Blinn-Phong, all lights, ray-traced hard shadows) with `normal` facing
    // the viewer and `geometricNormal` on the viewer's side; the diffuse texture filtered over a
    // footprint of 2^uvLod uv units (ray_cone.h). `mediumAbsorption`: that of the media on the
    // viewer's side of the surface, where the shadow rays start (MediumStack::absorption).
    glm::vec3 localColor(const SurfaceHit& hit, glm::vec3 normal, glm::vec3 geometricNormal, glm::vec3 toViewer,
                         RayStats& stats, bool shadowRays = true,
                         float uvLod = -std::numeric_limits<float>::infinity(), glm::vec3 mediumAbsorption = glm::vec3(0.0f)) const;

private:
    friend class EmbreeTreeBackend;  // the walk's backend (embree_tree_backend.h) reads the scene and settings

    const RayScene& rays_;
    WhittedSettings settings_;
    std::vector<SpotCone> cones_;  // per light
};

}  // namespace hybridlab
