#pragma once
// Ray tracing from the camera through pixel centres (optionally n x n supersampled for display
// images): the reference's recursive Whitted tracer at every pixel, all lights, hard shadows,
// parallel over image tiles and deterministic; with rays = "vulkan" the same on the Vulkan
// device's ray-tracing pipeline (device_rays.h). It is the whole of `rt_only` and of `whitted`,
// which may shade lens pixels with another model (LensPixelModel).
#include <functional>
#include <memory>

#include "common/device_rays/device_whitted_tracer.h"
#include "common/raytrace/whitted_tracer.h"
#include "techniques/parameter_binder.h"
#include "techniques/shared/ray_backend_parameters.h"
#include "techniques/shared/recursion_parameters.h"
#include "techniques/shared/traced_shading_parameters.h"
#include "techniques/technique.h"

namespace hybridlab {

struct CameraRayParameters {
    RecursionParameters recursion;
    int supersample{};
    TracedShadingParameters shading;
    RayBackendParameters rays;

    WhittedSettings tracerSettings() const {
        WhittedSettings s = recursion.settings();
        shading.applyTo(s);
        return s;
    }
};

// The recursion's parameters (with the importance cut-off's default), supersample, the shading's
// and rays.
ParameterBinder<CameraRayParameters> cameraRayParameters(double defaultImportanceCutoff);

// Shades the pixels whose first hit is a lens object by another model than the full ray tree
// (whitted's lens_model = "two_term"); they are counted as lens_pixels and rays_lens_pixels.
class LensPixelModel {
public:
    virtual ~LensPixelModel() = default;
    // The radiance of a camera ray; `tracer` traces the whole scene `rays`. Sets `lensPixel` where
    // this model (rather than `tracer` alone) shaded it.
    virtual glm::vec3 radiance(const WhittedTracer& tracer, const RayScene& rays, const Ray& ray, RayStats& stats, RayCone cone,
                               bool* lensPixel) const = 0;
};

class CameraRayTechnique : public Technique {
public:
    // Builds a scene's lens model in prepare(); empty: every pixel the full ray tree.
    using LensModelFactory = std::function<std::unique_ptr<LensPixelModel>(const Scene&)>;

    // A lens model traces on the CPU only (rays = "embree"; the technique declaring it checks).
    explicit CameraRayTechnique(const CameraRayParameters& params, LensModelFactory lensModel = {});

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

}  // namespace hybridlab
