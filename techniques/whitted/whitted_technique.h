#pragma once
// `whitted`: the reference. Recursive Whitted ray tracing from the camera through pixel centres
// (optionally n x n supersampled for display images), reflection and refraction to depth 10, the
// full ray tree, all lights, hard shadows, parallel over image tiles and deterministic; with
// rays = "vulkan" the same on the Vulkan device's ray-tracing pipeline (device_rays.h). With
// lens_model = "two_term", the pixels whose first hit is a lens object are shaded by Hakura &
// Snyder's two-term model instead (LensPixelModel). `rt_only` is this technique with another
// importance cut-off, created through the registry.
#include <functional>
#include <memory>

#include "common/device_rays/device_whitted_tracer.h"
#include "common/raytrace/whitted_tracer.h"
#include "techniques/shared/camera_ray_parameters.h"
#include "techniques/technique.h"

namespace hybridlab {

// Shades the pixels whose first hit is a lens object by another model than the full ray tree
// (lens_model = "two_term"); they are counted as lens_pixels and rays_lens_pixels.
class LensPixelModel {
public:
    virtual ~LensPixelModel() = default;
    // The radiance of a camera ray; `tracer` traces the whole scene `rays`. Sets `lensPixel` where
    // this model (rather than `tracer` alone) shaded it.
    virtual glm::vec3 radiance(const WhittedTracer& tracer, const RayScene& rays, const Ray& ray, RayStats& stats, RayCone cone,
                               bool* lensPixel) const = 0;
};

class WhittedTechnique : public Technique {
public:
    // Builds a scene's lens model in prepare(); empty: every pixel the full ray tree.
    using LensModelFactory = std::function<std::unique_ptr<LensPixelModel>(const Scene&)>;

    // A lens model traces on the CPU only (rays = "embree"; whittedTechniqueInfo checks).
    explicit WhittedTechnique(const CameraRayParameters& params, LensModelFactory lensModel = {});

    void prepare(SceneContext& context) override;
    FrameResult render(SceneContext& context, const FrameRequest& frame) override;

private:
    WhittedSettings settings_;
    int supersample_ = 1;
    bool onDevice_ = false;  // rays = "vulkan"
    LensModelFactory lensModelFactory_;
    std::unique_ptr<LensPixelModel> lensModel_;  // built once per scene
    std::unique_ptr<DeviceWhittedTracer> deviceTracer_;
};

TechniqueInfo whittedTechniqueInfo();

}  // namespace hybridlab
