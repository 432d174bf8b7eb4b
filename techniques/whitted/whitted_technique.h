#pragma once
// `whitted`: the reference. Recursive Whitted ray tracing from the camera through pixel centres
// (optionally n x n supersampled for display images), reflection and refraction to depth 10, the
// full ray tree, all lights, hard shadows. Parallel over image tiles; deterministic.
#include "common/raytrace/whitted_tracer.h"
#include "techniques/layered_em/two_term_tracer.h"
#include "techniques/technique.h"

namespace hybridlab {

class WhittedTechnique : public Technique {
public:
    static TechniqueInfo info();
    // The declared parameters, with the importance cut-off's default (0: the full ray tree).
    static std::vector<ParamSpec> parameterSpecs(double defaultImportanceCutoff);
    // The tracer settings from the parameters above that name them (max_depth, importance_cutoff,
    // blend, shadows); hybrid techniques declare the same ones.
    static WhittedSettings tracerSettings(const ParameterSet& params);

    explicit WhittedTechnique(const ParameterSet& params);

    void prepare(SceneContext& context) override;
    FrameResult render(SceneContext& context, const FrameRequest& frame) override;

private:
    WhittedSettings settings_;
    int supersample_ = 1;
    bool twoTermLenses_ = false;  // lens_model = two_term
    std::unique_ptr<TwoTermTracer> twoTerm_;  // its lens systems, built once per scene
};

}  // namespace hybridlab
