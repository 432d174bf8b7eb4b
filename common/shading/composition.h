// How a hit of the ray tree combines its local colour with its reflected and refracted radiance,
// and which of those rays it traces (DESIGN.md "The shading model"), written once for both ray
// backends and the rasterizer's environment mapping (shading_language.h).
//
// Composition at a hit, with local colour C, reflected radiance M, refracted radiance R:
//   o_m * M + (1 - o_m) * (o_r * R + (1 - o_r) * C)
// with o_m = reflectivity, or the exact unpolarised Fresnel reflectance when the material asks for
// it, and o_r = 1 - opacity. Total internal reflection sends everything to the reflected ray
// (R = M). Walewski 2019 eqs. (5)-(6) average this with the same expression taken in the other
// order (`walewski`, BlendRule::Walewski2019).
#ifndef COMPOSITION_H
#define COMPOSITION_H

#include "reflection_refraction.h"
#include "shading_language.h"

SHARED_BEGIN

// The composition (above), under the design's rule or Walewski 2019's average.
SHARED_FUNCTION vec3 compose(float om, float orr, vec3 M, vec3 R, vec3 C, bool walewski) {
    vec3 cm = om * M + (1.0f - om) * (orr * R + (1.0f - orr) * C);
    if (!walewski) return cm;
    vec3 cr = orr * R + (1.0f - orr) * (om * M + (1.0f - om) * C);  // Walewski eq. (6)
    return 0.5f * (cm + cr);
}

// The local colour C for which compose(om, orr, M, R, C, walewski) equals `composite` (both rules
// are affine in C with slope (1 - o_m)(1 - o_r)); `fallback` where that slope is too small for C to
// matter. Recovers the rasterizer's shadow-mapped C from its composed pixel.
SHARED_FUNCTION vec3 uncomposeLocal(float om, float orr, vec3 M, vec3 R, vec3 composite, vec3 fallback, bool walewski) {
    float slope = (1.0f - om) * (1.0f - orr);
    if (slope < 1e-4f) return fallback;
    return (composite - compose(om, orr, M, R, vec3(0.0f), walewski)) / slope;
}

// The side of a surface a ray arrives from: its normals turned towards the ray, and the indices of
// refraction on that side (n1) and beyond (n2).
struct ArrivalSide {
    bool entering;         // through the front face (against the geometric normal)
    vec3 geometricNormal;  // unit, on the ray's side
    vec3 shadingNormal;    // unit, on the ray's side
    float n1, n2;
};

SHARED_FUNCTION ArrivalSide arrivalSide(vec3 incoming, vec3 geometricNormal, vec3 shadingNormal, float ior, float ambientIor) {
    ArrivalSide side;
    side.entering = dot(incoming, geometricNormal) < 0.0f;
    side.geometricNormal = side.entering ? geometricNormal : -geometricNormal;
    side.shadingNormal = side.entering ? shadingNormal : -shadingNormal;
    side.n1 = side.entering ? ambientIor : ior;
    side.n2 = side.entering ? ior : ambientIor;
    return side;
}

// What a hit does with the rays it could spawn.
struct HitScattering {
    float reflectivity;  // o_m (the Fresnel reflectance for dielectrics)
    float transparency;  // o_r = 1 - opacity
    bool composes;       // false: the surface neither reflects nor refracts, or the depth limit was
                         // reached with depth_limit = "local"; its radiance is C alone
    bool tracesRays;     // composes, and above the depth limit
    bool tir;            // total internal reflection: R is M
    vec3 reflectedDirection, refractedDirection;  // where tracesRays (refracted: where o_r > 0, not tir)
    float weightM, weightR;  // the rays' weights in the hit's radiance (under tir M takes R's)
    bool traceM, traceR;     // traced: their effect is asked for and worth it under the cut-off
    bool localWeighs;        // C changes the composed radiance (below)
};

// The rays of a hit seen along unit `incoming` with shading normal `n` on its side (ArrivalSide),
// at ray-tree depth `depth` with weight `importance` in the pixel: the composition's weights, the
// depth limit (`maxDepth`; `depthLimitLocal`: C alone there, else the rays not traced count 0,
// the tree truncated), and the importance cut-off (Walewski 2019 §3.3: a ray whose weight in the
// pixel falls below `importanceCutoff` is not traced and C stands in for it). `traceReflection` and
// `traceRefraction`: the effects traced at this hit (TracedEffects).
SHARED_FUNCTION HitScattering scatterAtHit(vec3 incoming, vec3 n, float n1, float n2, float reflectivity, bool fresnel, float opacity,
                                           int depth, int maxDepth, bool depthLimitLocal, float importance, float importanceCutoff,
                                           bool traceReflection, bool traceRefraction) {
    HitScattering s;
    s.transparency = 1.0f - opacity;
    float orr = s.transparency;
    float cosi = max(-dot(incoming, n), 0.0f);
    float om = fresnel ? fresnelDielectric(cosi, n1, n2) : reflectivity;
    s.reflectivity = om;
    // At the limit with "weighted" the rays not traced count 0 (under total internal reflection too).
    s.composes = (om > 0.0f || orr > 0.0f) && !(depth >= maxDepth && depthLimitLocal);
    s.tracesRays = s.composes && depth < maxDepth;
    s.refractedDirection = vec3(0.0f);
    s.tir = s.tracesRays && orr > 0.0f && !refractDirection(incoming, n, n1 / n2, s.refractedDirection);
    s.reflectedDirection = s.tracesRays ? reflectDirection(incoming, n) : vec3(0.0f);
    // Total internal reflection sends everything to the reflected ray.
    s.weightM = s.tir ? om + (1.0f - om) * orr : om;
    s.weightR = s.tir ? 0.0f : (1.0f - om) * orr;
    s.traceM = s.tracesRays && traceReflection && s.weightM > 0.0f && importance * s.weightM >= importanceCutoff;
    s.traceR = s.tracesRays && !s.tir && traceRefraction && s.weightR > 0.0f && importance * s.weightR >= importanceCutoff;
    // C weighs (1 - o_m)(1 - o_r) in the composition under both rules. It also stands in for a ray
    // not traced (the importance cut-off): the reflected one, weighted by weightM (which the
    // refracted one copies under total internal reflection), or the refracted one, whose weight
    // carries the factor o_r under both rules. Where none of these weighs (clear glass, total
    // internal reflection, a perfect mirror, each with its rays traced), the composed radiance does
    // not depend on C: a tree may skip its shading and shadow rays, C = 0 leaving the sum bit for
    // bit the same.
    s.localWeighs = !s.composes || (om < 1.0f && orr < 1.0f) ||
                    (s.tracesRays && ((!s.traceM && s.weightM > 0.0f) || (!s.tir && !s.traceR && orr > 0.0f)));
    return s;
}

SHARED_END

#endif
