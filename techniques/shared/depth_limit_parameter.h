#pragma once
// The `depth_limit` parameter of the reference and every ray-tracing technique, declared once:
// what a hit at the recursion limit (max_depth) returns (DepthLimit, whitted_tracer.h).
#include "common/raytrace/whitted_tracer.h"
#include "techniques/parameters.h"

namespace hybridlab {

inline ParamSpec depthLimitParameterSpec() {
    return ParamSpec::choice("depth_limit", "weighted", {"weighted", "local"},
                             "a hit at max_depth: its local colour weighted as the composition weights it, the rays it "
                             "would trace counting 0 (the truncated ray tree, as POV-Ray), or its local colour alone");
}

inline DepthLimit depthLimitSetting(const ParameterSet& p) {
    return p.getChoice("depth_limit") == "local" ? DepthLimit::Local : DepthLimit::Weighted;
}

}  // namespace hybridlab
