// Beer-Lambert absorption along a ray's segments, written once for both ray backends
// (shading_language.h); common/raytrace/medium_stack.h states the rule and keeps the media a ray
// is in.
#ifndef ABSORPTION_H
#define ABSORPTION_H

#include "shading_language.h"

SHARED_BEGIN

// The transmittance exp(-a len) of a segment of length `len` in media of total absorption `a`.
// Exactly 1 for a = 0 (also for an infinite length, where exp(-0 * inf) would be NaN).
SHARED_FUNCTION vec3 segmentTransmittance(vec3 a, float len) {
    vec3 t = vec3(1.0f);
    for (int c = 0; c < 3; ++c)
        if (a[c] > 0.0f) t[c] = exp(-a[c] * len);
    return t;
}

// A shadow ray's optical depth gained at a crossing, at distance t, of a surface of absorption a:
// +-a (D - t) towards a light at distance D, entering (+) or leaving (-); -+a t towards a
// directional light (D < 0 here: infinitely far), which lies outside every medium. Summed over the
// crossings in any order, with the start's absorption times D, it is the integral of the
// absorption along the ray.
SHARED_FUNCTION vec3 crossingOpticalDepth(vec3 a, bool entering, float t, float D) {
    if (D >= 0.0f) return (entering ? 1.0f : -1.0f) * a * (D - t);
    return (entering ? -1.0f : 1.0f) * a * t;
}

// The transmittance of a shadow ray that nothing opaque stopped, towards a light at distance D
// (< 0: a directional light): the product of its occluders' transmittances times exp(-tau), tau
// the optical depth summed over its crossings (crossingOpticalDepth) plus the absorption of the
// media it starts in times D (medium_stack.h).
SHARED_FUNCTION vec3 shadowRayTransmittance(vec3 occluders, vec3 crossingsOpticalDepth, vec3 startAbsorption, float D) {
    vec3 opticalDepth = crossingsOpticalDepth;
    if (D >= 0.0f) opticalDepth += startAbsorption * D;
    if (opticalDepth == vec3(0.0f)) return occluders;
    // Negative only where crossings do not pair up (an open or overlapping mesh): no absorption.
    return occluders * segmentTransmittance(max(opticalDepth, vec3(0.0f)), 1.0f);
}

SHARED_END

#endif
