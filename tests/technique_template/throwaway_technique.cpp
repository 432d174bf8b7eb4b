#include "techniques/throwaway/throwaway_technique.h"

#include "techniques/make_technique_info.h"

namespace hybridlab {

TechniqueInfo ThrowawayTechnique::info() {
    // Every field of ThrowawayParameters bound to its parameter, once.
    ParameterBinder<ThrowawayParameters> parameters;
    parameters.bind(&ThrowawayParameters::level, ParamSpec::real("level", 0.5, 0.0, 1.0, "the grey level of every pixel"));
    return makeTechniqueInfo("throwaway", "A template: one colour", std::move(parameters),
                             [](const ThrowawayParameters& p) { return std::make_unique<ThrowawayTechnique>(p); });
}

ThrowawayTechnique::ThrowawayTechnique(const ThrowawayParameters& params) : level_(params.level) {}

FrameResult ThrowawayTechnique::render(SceneContext& context, const FrameRequest& frame) {
    (void)context;
    if (!pipeline_) {
        const VulkanDevice& device = *VulkanDevice::shared();
        layout_ = createPipelineLayout(device, {}, sizeof(float));
        pipeline_ = createComputePipeline(device, "throwaway_fill.comp", layout_);
    }
    FrameResult result;
    result.image = Image(frame.width, frame.height, glm::vec4(level_, level_, level_, 1.0f));
    return result;
}

}  // namespace hybridlab
