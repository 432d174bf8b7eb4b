#include "techniques/whitted/whitted_technique.h"

#include "common/core/input_error.h"
#include "techniques/shared/two_term_tracer.h"
#include "techniques/make_technique_info.h"
#include "techniques/shared/camera_ray_technique.h"

namespace hybridlab {

namespace {

struct WhittedParameters {
    CameraRayParameters camera;
    bool twoTermLenses{};  // lens_model = "two_term"
};

// Hakura & Snyder 2001 §6's uniformly sampled ray tracing restricted to the two-term model.
class TwoTermLenses : public LensPixelModel {
public:
    explicit TwoTermLenses(const Scene& scene) : tracer_(scene) {}
    glm::vec3 radiance(const WhittedTracer& tracer, const RayScene& rays, const Ray& ray, RayStats& stats, RayCone cone,
                       bool* lensPixel) const override {
        return tracer_.radiance(tracer, rays, ray, stats, cone, lensPixel);
    }

private:
    TwoTermTracer tracer_;  // its lens systems
};

}  // namespace

TechniqueInfo whittedTechniqueInfo() {
    ParameterBinder<WhittedParameters> parameters;
    parameters.bind(&WhittedParameters::camera, cameraRayParameters(/*defaultImportanceCutoff=*/0.0));
    parameters.bind(&WhittedParameters::twoTermLenses,
                    ParamSpec::choice("lens_model", "full", {"full", "two_term"},
                                      "pixels whose first hit is a lens object: the full ray tree, or the two-term greedy model "
                                      "(Hakura & Snyder 2001 §3: uniformly sampled ray tracing as layered_em approximates it)"),
                    {false, true});
    return makeTechniqueInfo(
        "whitted", "Reference: full recursive Whitted ray tracing (Embree), hard shadows, reflection and refraction to depth 10",
        std::move(parameters),
        [](const WhittedParameters& p) {
            if (!p.twoTermLenses) return std::make_unique<CameraRayTechnique>(p.camera);
            if (p.camera.rays.onDevice) throw InputError("lens_model = \"two_term\" traces on the CPU only; it needs rays = \"embree\"");
            return std::make_unique<CameraRayTechnique>(p.camera, [](const Scene& scene) { return std::make_unique<TwoTermLenses>(scene); });
        },
        /*relativeCost=*/1.0);  // the unit
}

}  // namespace hybridlab
