#pragma once
// The parameters of ray tracing from the camera, which `whitted` and `rt_only` both take: the
// recursion (with its importance cut-off's default, the one thing in which they differ),
// supersampling for display images, the traced shading and the ray backend.
#include "common/raytrace/whitted_tracer.h"
#include "techniques/parameter_binder.h"
#include "techniques/shared/ray_backend_parameters.h"
#include "techniques/shared/recursion_parameters.h"
#include "techniques/shared/traced_shading_parameters.h"

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

}  // namespace hybridlab
