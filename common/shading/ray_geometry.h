// Where secondary rays start and what their ray cones cover, written once for both ray backends
// (shading_language.h).
#ifndef RAY_GEOMETRY_H
#define RAY_GEOMETRY_H

#include "shading_language.h"

SHARED_BEGIN

// p offset along the unit geometric normal n towards the side the new ray leaves from, so that it
// cannot re-hit its own surface: Wächter & Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems (2019), ch. 6. The offset grows with the magnitude of the
// coordinates, so one rule works at every scene scale.
SHARED_FUNCTION vec3 offsetRayOrigin(vec3 p, vec3 n) {
    const float kOrigin = 1.0f / 32.0f, kFloatScale = 1.0f / 65536.0f, kIntScale = 256.0f;
    vec3 offset;
    for (int i = 0; i < 3; ++i) {
        int ofi = int(kIntScale * n[i]);
        float pi = intBitsToFloat(floatBitsToInt(p[i]) + (p[i] < 0.0f ? -ofi : ofi));
        offset[i] = abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : pi;
    }
    return offset;
}

// log2 of a ray cone's footprint in uv units at a hit (Akenine-Möller et al., "Texture Level of
// Detail Strategies for Real-Time Ray Tracing", Ray Tracing Gems ch. 20): the chapter's level of
// detail Delta_0 + log2 |W| - log2 |n . d| without the texture's size (textureUvUnitLod adds it),
// with Delta_0 = uvDensityLod the triangle's 0.5 log2(uv area / world area) and W the cone's width
// at the hit. -inf without a footprint.
SHARED_FUNCTION float uvFootprintLod(float uvDensityLod, float coneWidthAtHit, vec3 direction, vec3 geometricNormal) {
    if (coneWidthAtHit <= 0.0f) return -SHARED_INFINITY;
    float cosine = max(abs(dot(direction, geometricNormal)), 1e-4f);
    return uvDensityLod + log2(coneWidthAtHit / cosine);
}

SHARED_END

#endif
