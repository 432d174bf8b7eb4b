#pragma once
// `rt_only`: Walewski 2019's "RAYT ONLY" variant (Tables 5-6): primary rays from the camera and
// every effect ray traced, no rasterisation and no heuristic, with the importance cut-off of the
// paper's Listing 8c. It is the reference's tracer with a cut-off: the `whitted` technique from
// the registry under another name and default (kTracedImportanceCutoff), so that one
// implementation serves both.
#include "techniques/technique.h"

namespace hybridlab {

TechniqueInfo rtOnlyTechniqueInfo();

}  // namespace hybridlab
