#include "techniques/rt_only/rt_only_technique.h"

#include "techniques/shared/camera_ray_parameters.h"

namespace hybridlab {

TechniqueInfo rtOnlyTechniqueInfo() {
    const ParameterBinder<CameraRayParameters> parameters = cameraRayParameters(kTracedImportanceCutoff);
    parameters.checkEveryFieldBound("technique rt_only");
    TechniqueInfo info{"rt_only", "Walewski 2019's ray-tracing-only variant: everything ray traced from the camera, with an importance cut-off",
            parameters.specs(),
            // The reference's technique, found in the registry, with these values and every pixel the full ray tree.
            [](const ParameterSet& values) {
                ParameterSet reference = values;
                reference.set("lens_model", std::string("full"));
                return findTechnique("whitted").create(reference);
            },
            /*relativeCost=*/0.5,  // 0.46-0.54 of the reference at 320x180 (whitted-classic, cornell-mirror-glass)
            /*bakeCommand=*/std::nullopt,
            /*searchSpace=*/{}};
    // The ray tree's depth and importance cut-off (Walewski 2019's rt_only cuts at 0.01).
    using S = SearchDimension::Scale;
    info.searchSpace = {{"max_depth", {2LL, 4LL, 10LL}, S::Linear}, {"importance_cutoff", {0.0, 0.01, 0.05, 0.1}, S::Linear}};
    return info;
}

}  // namespace hybridlab
