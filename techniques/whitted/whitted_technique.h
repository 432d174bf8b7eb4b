#pragma once
// `whitted`: the reference. Recursive Whitted ray tracing from the camera through pixel centres
// (optionally n x n supersampled for display images), reflection and refraction to depth 10, the
// full ray tree, all lights, hard shadows. Parallel over image tiles; deterministic. With
// rays = "vulkan" the same on the Vulkan device's ray-tracing pipeline (common/device_rays).
#include "common/device_rays/device_whitted_tracer.h"
#include "common/raytrace/whitted_tracer.h"
#include "techniques/layered_em/two_term_tracer.h"
#include "techniques/technique.h"

namespace hybridlab {

class WhittedTechnique : public Technique {
public:
    static TechniqueInfo info();
    // The recursion's parameters (max_depth, importance_cutoff, blend), declared once for every
    // technique that traces secondary rays, with the importance cut-off's default (0: the full ray tree).
    static std::vector<ParamSpec> recursionParameterSpecs(double defaultImportanceCutoff);
    // Tracer settings with those three from `params`, the others WhittedSettings' defaults.
    static WhittedSettings recursionSettings(const ParameterSet& params);
    // The declared parameters: the recursion's, supersample, shadows and texture_filter.
    static std::vector<ParamSpec> parameterSpecs(double defaultImportanceCutoff);
    // The tracer settings from the parameters above that name them (the recursion's, shadows,
    // texture_filter); heuristic_rt declares the same ones.
    static WhittedSettings tracerSettings(const ParameterSet& params);

    explicit WhittedTechnique(const ParameterSet& params);

    void prepare(SceneContext& context) override;
    FrameResult render(SceneContext& context, const FrameRequest& frame) override;

private:
    WhittedSettings settings_;
    int supersample_ = 1;
    bool twoTermLenses_ = false;  // lens_model = two_term
    std::unique_ptr<TwoTermTracer> twoTerm_;  // its lens systems, built once per scene
    bool onDevice_ = false;                   // rays = "vulkan"
    std::unique_ptr<DeviceWhittedTracer> deviceTracer_;
};

}  // namespace hybridlab
