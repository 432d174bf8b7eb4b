#pragma once
// `whitted`: the reference. Recursive Whitted ray tracing from the camera through pixel centres
// (optionally n x n supersampled for display images), reflection and refraction to depth 10, the
// full ray tree, all lights, hard shadows (CameraRayTechnique); with lens_model = "two_term", the
// pixels whose first hit is a lens object shaded by Hakura & Snyder's two-term model instead.
#include "techniques/technique.h"

namespace hybridlab {

TechniqueInfo whittedTechniqueInfo();

}  // namespace hybridlab
