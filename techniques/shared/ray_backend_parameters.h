#pragma once
// Where a technique's rays run, declared once for every technique that traces: `rays = "embree"`
// (the CPU, RayScene) or `rays = "vulkan"` (the ray-tracing Vulkan device, DeviceRayScene;
// device_rays.h).
#include "techniques/parameter_binder.h"

namespace hybridlab {

struct RayBackendParameters {
    bool onDevice{};  // rays = "vulkan"
};

inline ParameterBinder<RayBackendParameters> rayBackendParameters() {
    ParameterBinder<RayBackendParameters> b;
    b.bind(&RayBackendParameters::onDevice,
           ParamSpec::choice("rays", "embree", {"embree", "vulkan"},
                             "where rays are traced: Embree on the CPU, or the Vulkan device's ray-tracing pipeline"),
           {false, true});
    return b;
}

}  // namespace hybridlab
