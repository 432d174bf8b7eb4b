#pragma once
// Recursive Whitted ray tracing (Whitted 1980; Walewski 2019 Listing 8c with the composition rule
// of DESIGN.md): hard shadows from every light, reflection and refraction to a depth limit, the
// local colour at the limit, the sky on a miss. The reference technique calls it from camera rays;
// hybrid techniques call shade() from a G-buffer texel.
#include <vector>

#include "common/raytrace/ray_scene.h"
#include "common/raytrace/ray_stats.h"
#include "common/raytrace/shading.h"

namespace hybridlab {

struct WhittedSettings {
    int maxDepth = 10;             // secondary bounces; a hit at this depth returns its local colour
    float importanceCutoff = 0.0f; // a secondary ray whose weight in the pixel falls below this is not
                                   // traced and the surface's local colour stands in, as at the depth
                                   // limit (0: the full ray tree)
    BlendRule blend = BlendRule::Design;
    bool shadows = true;           // shadow rays; off: every light unshadowed (to compare with raster without shadows)
};

class WhittedTracer {
public:
    WhittedTracer(const RayScene& rays, WhittedSettings settings);

    const WhittedSettings& settings() const { return settings_; }

    // Radiance arriving along `ray` whose hit would be at recursion depth `depth` (camera rays: 0).
    // `importance` is the ray's weight in the pixel.
    glm::vec3 radiance(const Ray& ray, int depth, float importance, RayStats& stats) const;

    // Full Whitted shading of a surface hit seen along unit direction `incoming` (towards the
    // surface): local colour with ray-traced shadows, composed with recursive reflection and
    // refraction.
    glm::vec3 shade(const SurfaceHit& hit, glm::vec3 incoming, int depth, float importance, RayStats& stats) const;

    // The local colour C (Blinn-Phong, all lights, ray-traced hard shadows) with `normal` facing
    // the viewer and `geometricNormal` on the viewer's side.
    glm::vec3 localColor(const SurfaceHit& hit, glm::vec3 normal, glm::vec3 geometricNormal, glm::vec3 toViewer,
                         RayStats& stats) const;

private:
    const RayScene& rays_;
    WhittedSettings settings_;
    std::vector<SpotCone> cones_;  // per light
};

}  // namespace hybridlab
