#pragma once
// The media a ray travels in and Beer-Lambert absorption along it, as the C++ reads them: the stack
// and its rule are common/shading/medium_stack.h, the transmittances common/shading/absorption.h,
// each written once for both ray backends.
#include "common/shading/absorption.h"
#include "common/shading/medium_stack.h"

namespace hybridlab {

using shading_language::kMediumCapacity;
using shading_language::MediumEntry;
using shading_language::MediumStack;
using shading_language::mediumAbsorbs;
using shading_language::mediumEnter;
using shading_language::mediumLeave;

// The stack of a camera ray, shared: default arguments take it instead of a temporary.
inline const MediumStack kAmbientMedium;

using shading_language::crossingOpticalDepth;
using shading_language::segmentTransmittance;
using shading_language::shadowRayTransmittance;

}  // namespace hybridlab
