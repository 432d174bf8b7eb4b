#include "techniques/rt_only/rt_only_technique.h"

#include "techniques/make_technique_info.h"
#include "techniques/shared/camera_ray_technique.h"

namespace hybridlab {

TechniqueInfo rtOnlyTechniqueInfo() {
    return makeTechniqueInfo(
        "rt_only", "Walewski 2019's ray-tracing-only variant: everything ray traced from the camera, with an importance cut-off",
        cameraRayParameters(kTracedImportanceCutoff),
        [](const CameraRayParameters& p) { return std::make_unique<CameraRayTechnique>(p); },
        /*relativeCost=*/0.5);  // 0.46-0.54 of the reference at 320x180 (whitted-classic, cornell-mirror-glass)
}

}  // namespace hybridlab
