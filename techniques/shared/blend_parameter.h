#pragma once
// The `blend` parameter, declared once for every technique that composes reflections and
// refractions (the raster technique and the recursion group): the composition rule (BlendRule,
// common/raytrace/shading.h).
#include <vector>

#include "common/raytrace/shading.h"
#include "techniques/parameters.h"

namespace hybridlab {

inline ParamSpec blendParameterSpec() {
    return ParamSpec::choice("blend", "design", {"design", "walewski2019"},
                             "composition rule: design = o_m*M + (1-o_m)*(o_r*R + (1-o_r)*C) (o_m reflectivity or Fresnel, "
                             "o_r 1-opacity), or walewski2019 = that averaged with the other order (Walewski 2019 eqs. (5)-(6))");
}

// The rule for each of the spec's choices, in their order.
inline std::vector<BlendRule> blendParameterValues() { return {BlendRule::Design, BlendRule::Walewski2019}; }

}  // namespace hybridlab
