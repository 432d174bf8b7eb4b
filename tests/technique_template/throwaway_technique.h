#pragma once
// A technique folder as a new technique starts: copied into techniques/ by
// tests/techniques/technique_folder_check.py, which proves that one folder and one registry line are all it
// takes. Fills the frame with one colour on the Vulkan device.
#include "common/raster/pipelines.h"
#include "techniques/technique.h"

namespace hybridlab {

// The technique's parameters, each bound to its spec in info().
struct ThrowawayParameters {
    float level{};
};

class ThrowawayTechnique : public Technique {
public:
    static TechniqueInfo info();
    explicit ThrowawayTechnique(const ThrowawayParameters& params);

    FrameResult render(SceneContext& context, const FrameRequest& frame) override;

private:
    float level_ = 0.5f;
    UniquePipelineLayout layout_;
    UniquePipeline pipeline_;
};

}  // namespace hybridlab
