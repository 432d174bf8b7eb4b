#include "techniques/rt_only/rt_only_technique.h"

#include "techniques/shared/camera_ray_parameters.h"

namespace hybridlab {

TechniqueInfo rtOnlyTechniqueInfo() {
    const ParameterBinder<CameraRayParameters> parameters = cameraRayParameters(kTracedImportanceCutoff);
    parameters.checkEveryFieldBound("technique rt_only");
    return {"rt_only", "Walewski 2019's ray-tracing-only variant: everything ray traced from the camera, with an importance cut-off",
            parameters.specs(),
            // The reference's technique, found in the registry, with these values and every pixel the full ray tree.
            [](const ParameterSet& values) {
                ParameterSet reference = values;
                reference.set("lens_model", std::string("full"));
                return findTechnique("whitted").create(reference);
            },
            /*relativeCost=*/0.5,  // 0.46-0.54 of the reference at 320x180 (whitted-classic, cornell-mirror-glass)
            /*bakeCommand=*/std::nullopt};
}

}  // namespace hybridlab
