#include "techniques/rt_only/rt_only_technique.h"

#include "techniques/shared/device_rays.h"
#include "techniques/whitted/whitted_technique.h"

namespace hybridlab {

TechniqueInfo rtOnlyTechniqueInfo() {
    return {"rt_only",
            "Walewski 2019's ray-tracing-only variant: everything ray traced from the camera, with an importance cut-off",
            [] {
                std::vector<ParamSpec> specs = WhittedTechnique::parameterSpecs(kRtOnlyImportanceCutoff);
                specs.push_back(raysParameterSpec());
                return specs;
            }(),
            [](const ParameterSet& p) { return std::make_unique<WhittedTechnique>(p); },
            /*relativeCost=*/0.5};  // 0.46-0.54 of the reference at 320x180 (whitted-classic, cornell-mirror-glass)
}

}  // namespace hybridlab
