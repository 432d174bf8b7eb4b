#pragma once
// How a hybrid's ray stage on the Vulkan device is launched (with rays = "vulkan";
// DeviceGBufferTracer::setCompactLaunch): over the texels its classification pass lists
// (`launch = "compact"`), so that no invocation is launched only to return, or one invocation per
// G-buffer texel (`"full"`, the launch before compaction, kept to compare the two). The images are
// the same either way.
#include "techniques/parameter_binder.h"

namespace hybridlab {

struct DeviceLaunchParameters {
    bool compact{};  // launch = "compact"
};

inline ParameterBinder<DeviceLaunchParameters> deviceLaunchParameters() {
    ParameterBinder<DeviceLaunchParameters> b;
    b.bind(&DeviceLaunchParameters::compact,
           ParamSpec::choice("launch", "compact", {"compact", "full"},
                             "rays = \"vulkan\": the ray stage launched over the texels a classification pass lists, or one "
                             "invocation per texel (the same images)"),
           {true, false});
    return b;
}

}  // namespace hybridlab
