#include "techniques/heuristic_rt/heuristic.h"

#include <algorithm>
#include <cmath>

namespace hybridlab {

double raysPerPixel(Effect effect, int lightCount) {
    switch (effect) {
        case Effect::Shadows: return lightCount;
        case Effect::Reflection: return lightCount + 1;
        case Effect::Refraction: return lightCount + 4;
    }
    return 0.0;
}

ObjectScore scoreObject(const ObjectObservation& o, int lightCount, double previousSelectionImportance) {
    ObjectScore s;
    const double bx = o.boundsCenterNdc.x, by = o.boundsCenterNdc.y;
    s.P = std::max(1.0 - std::sqrt(bx * bx + by * by), 0.0) * 0.99 + 0.01;
    s.V = o.visiblePixels * s.P / o.distance;  // eq. (1)
    s.Q = raysPerPixel(Effect::Shadows, lightCount);
    if (o.reflective) s.Q += raysPerPixel(Effect::Reflection, lightCount);
    if (o.refractive) s.Q += raysPerPixel(Effect::Refraction, lightCount);
    s.C = o.visiblePixels * s.Q * o.estimatedCost;  // eq. (2)
    s.R = ((o.selectedLastFrame ? 1.0 : 0.0) * previousSelectionImportance + s.V) * o.staticRelevance;  // eq. (3)
    return s;
}

}  // namespace hybridlab
