#pragma once
// The recursion's parameters, declared once for every technique that traces secondary rays (the
// reference, rt_only, heuristic_rt, ssr_fallback's fallback rays): max_depth, importance_cutoff,
// blend and depth_limit, the WhittedSettings they give.
#include "common/raytrace/whitted_tracer.h"
#include "techniques/parameter_binder.h"
#include "techniques/shared/blend_parameter.h"

namespace hybridlab {

// The importance cut-off of rt_only and of the hybrids' rays (Walewski 2019 Listing 8c). Walewski
// gives no value; 0.01 (a secondary ray worth under 1 % of its pixel is not traced) is our default,
// a parameter like every other. The reference's is 0, the full ray tree.
inline constexpr double kTracedImportanceCutoff = 0.01;

struct RecursionParameters {
    int maxDepth{};
    float importanceCutoff{};
    BlendRule blend{};
    DepthLimit depthLimit{};

    // Tracer settings with these four, the others WhittedSettings' defaults.
    WhittedSettings settings() const {
        WhittedSettings s;
        s.maxDepth = maxDepth;
        s.importanceCutoff = importanceCutoff;
        s.blend = blend;
        s.depthLimit = depthLimit;
        return s;
    }
};

// With the importance cut-off's default (0: the full ray tree).
inline ParameterBinder<RecursionParameters> recursionParameters(double defaultImportanceCutoff) {
    ParameterBinder<RecursionParameters> b;
    b.bind(&RecursionParameters::maxDepth, ParamSpec::integer("max_depth", 10, 0, 64, "secondary bounces before the local colour is returned"));
    b.bind(&RecursionParameters::importanceCutoff,
           ParamSpec::real("importance_cutoff", defaultImportanceCutoff, 0.0, 1.0,
                           "do not trace secondary rays whose weight in the pixel is below this (0: full ray tree)"));
    b.bind(&RecursionParameters::blend, blendParameterSpec(), blendParameterValues());
    b.bind(&RecursionParameters::depthLimit,
           ParamSpec::choice("depth_limit", "weighted", {"weighted", "local"},
                             "a hit at max_depth: its local colour weighted as the composition weights it, the rays it "
                             "would trace counting 0 (the truncated ray tree, as POV-Ray), or its local colour alone"),
           {DepthLimit::Weighted, DepthLimit::Local});
    return b;
}

}  // namespace hybridlab
