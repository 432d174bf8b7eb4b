#pragma once
// `rt_only`: Walewski 2019's "RAYT ONLY" variant (Tables 5-6): primary rays from the camera and
// every effect ray traced, no rasterisation and no heuristic, with the importance cut-off of the
// paper's Listing 8c. It is the reference's tracer with a cut-off, so it is WhittedTechnique
// under another name and default: one implementation serves both.
#include "techniques/technique.h"

namespace hybridlab {

// Walewski gives no value for the cut-off; 0.01 (a secondary ray worth under 1 % of its pixel is
// not traced) is our default, a parameter like every other.
inline constexpr double kRtOnlyImportanceCutoff = 0.01;

TechniqueInfo rtOnlyTechniqueInfo();

}  // namespace hybridlab
