// Mirror reflection, Snell refraction and the exact Fresnel reflectance of a dielectric, written
// once for both ray backends and the rasterizer's environment mapping (shading_language.h).
#ifndef REFLECTION_REFRACTION_H
#define REFLECTION_REFRACTION_H

#include "shading_language.h"

SHARED_BEGIN

// The mirror direction of incident direction d about normal n (both unit; d towards the surface).
SHARED_FUNCTION vec3 reflectDirection(vec3 d, vec3 n) { return d - 2.0f * dot(d, n) * n; }

// Snell refraction of unit incident d through unit normal n (n against d) with eta = n1 / n2.
// False under total internal reflection (`refracted` then 0).
SHARED_FUNCTION bool refractDirection(vec3 d, vec3 n, float eta, OUT_PARAM(vec3) refracted) {
    float cosi = -dot(d, n);
    float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
    refracted = vec3(0.0f);
    if (k < 0.0f) return false;
    refracted = normalize(eta * d + (eta * cosi - sqrt(k)) * n);
    return true;
}

// The exact unpolarised Fresnel reflectance (the mean of the s- and p-polarised ones) for the
// cosine of the incidence angle and indices n1, n2; 1 under total internal reflection. At normal
// incidence ((n1 - n2) / (n1 + n2))^2.
SHARED_FUNCTION float fresnelDielectric(float cosIncident, float n1, float n2) {
    float cosi = clamp(cosIncident, 0.0f, 1.0f);
    float sint2 = (n1 / n2) * (n1 / n2) * (1.0f - cosi * cosi);
    if (sint2 >= 1.0f) return 1.0f;
    float cost = sqrt(1.0f - sint2);
    float rs = (n1 * cosi - n2 * cost) / (n1 * cosi + n2 * cost);
    float rp = (n2 * cosi - n1 * cost) / (n2 * cosi + n1 * cost);
    return 0.5f * (rs * rs + rp * rp);
}

SHARED_END

#endif
