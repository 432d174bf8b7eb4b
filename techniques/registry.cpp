// The one place that lists the techniques. Adding a technique: one folder, one line here.
#include "techniques/heuristic_rt/heuristic_rt_technique.h"
#include "techniques/layered_em/layered_em_technique.h"
#include "techniques/raster/raster_technique.h"
#include "techniques/rt_only/rt_only_technique.h"
#include "techniques/ssr_fallback/ssr_fallback_technique.h"
#include "techniques/technique.h"
#include "techniques/whitted/whitted_technique.h"

namespace hybridlab {

const std::vector<TechniqueInfo>& registeredTechniques() {
    static const std::vector<TechniqueInfo> registry = {
        whittedTechniqueInfo(),
        RasterTechnique::info(),
        rtOnlyTechniqueInfo(),
        HeuristicRtTechnique::info(),
        SsrFallbackTechnique::info(),
        LayeredEmTechnique::info(),
    };
    return registry;
}

}  // namespace hybridlab
