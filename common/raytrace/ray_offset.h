#pragma once
// Secondary-ray origins that cannot re-hit their own surface: Wächter & Binder, "A Fast and Robust
// Method for Avoiding Self-Intersection", Ray Tracing Gems (2019), ch. 6. The offset grows with the
// magnitude of the coordinates, so one rule works at every scene scale.
#include "common/shading/ray_geometry.h"

namespace hybridlab {

// p offset along the unit geometric normal n (towards the side the new ray leaves from); written
// once for both ray backends in common/shading/ray_geometry.h.
using shading_language::offsetRayOrigin;

}  // namespace hybridlab
