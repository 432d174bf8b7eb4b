#include "techniques/shared/camera_ray_parameters.h"

namespace hybridlab {

ParameterBinder<CameraRayParameters> cameraRayParameters(double defaultImportanceCutoff) {
    ParameterBinder<CameraRayParameters> b;
    b.bind(&CameraRayParameters::recursion, recursionParameters(defaultImportanceCutoff));
    b.bind(&CameraRayParameters::supersample,
           ParamSpec::integer("supersample", 1, 1, 16, "n x n samples per pixel for display images (metrics use 1)"));
    b.bind(&CameraRayParameters::shading, tracedShadingParameters());
    b.bind(&CameraRayParameters::rays, rayBackendParameters());
    return b;
}

}  // namespace hybridlab
