#pragma once
// Uniformly sampled ray tracing restricted to the two-term model (Hakura & Snyder 2001 §6, the
// comparison of their results table): where a camera ray's first hit is a lens object, the pixel
// is the two greedy paths through its lens system (lens_paths.h), each outgoing ray followed into
// the environment to its first front-facing hit (as outgoing_records.h records it) and shaded by the
// reference tracer there, or the sky; T F_T G_T + R F_R G_R. Elsewhere the full Whitted tracer.
#include <memory>
#include <vector>

#include "common/raytrace/whitted_tracer.h"
#include "techniques/shared/lens_paths.h"
#include "techniques/shared/lens_system.h"

namespace hybridlab {

class TwoTermTracer {
public:
    // Builds every lens system's ray scenes (once per scene).
    explicit TwoTermTracer(const Scene& scene);
    const Scene& scene() const { return scene_; }

    // The pixel's radiance for a camera ray; `tracer` traces the whole scene `rays`. Rays counted
    // in `stats` (lens-system and environment queries as refraction and reflection rays);
    // `lensPixel` (if given) tells whether the two-term model shaded it.
    glm::vec3 radiance(const WhittedTracer& tracer, const RayScene& rays, const Ray& ray, RayStats& stats, RayCone cone = {},
                       bool* lensPixel = nullptr) const;

    // The environment's radiance along an outgoing ray of a lens system.
    glm::vec3 environmentRadiance(const WhittedTracer& tracer, const LensSystem& system, Ray ray, RayStats& stats) const;

private:
    const Scene& scene_;
    std::vector<std::unique_ptr<LensSystem>> systems_;
    std::vector<int> systemOfObject_;  // per scene object: its lens system, -1
    LensPathSettings paths_;
};

}  // namespace hybridlab
