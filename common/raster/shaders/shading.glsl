// common/raytrace/shading.h and shading.cpp in GLSL (DESIGN.md "The shading model"): the same
// functions, in the same order of operations; RasterLighting (tests/raster/test_raster_lighting.cpp)
// holds the lighting pass and the C++ to the same numbers. Change one, change the other.
#ifndef SHADING_GLSL
#define SHADING_GLSL

#include "cube_map.glsl"

#include "raster_records.h"  // LightData, kLight*

// As LightSample.
struct LightSample {
    vec3 radiance;
    vec3 toLight;    // unit
    float distance;  // infinity for directional lights
};

// As sampleLight(const Light&, const SpotCone&, glm::vec3): inverse-square falloff for point
// and spot lights, and the spot cone's smoothstep written out as in the C++.
LightSample sampleLight(LightData light, vec3 p) {
    LightSample s;
    vec3 e = light.radiance.rgb;
    uint type = uint(light.radiance.a);
    if (type == kLightDirectional) {
        s.toLight = -light.direction.xyz;
        s.distance = 1.0 / 0.0;
        s.radiance = e;
        return s;
    }
    vec3 d = light.position.xyz - p;
    float d2 = dot(d, d);
    s.distance = sqrt(d2);
    s.toLight = d / s.distance;
    s.radiance = e / d2;
    if (type == kLightSpot) {
        float cosAngle = dot(-s.toLight, light.direction.xyz);
        float cosOuter = light.direction.w, cosInner = light.position.w;
        float x = cosInner > cosOuter ? clamp((cosAngle - cosOuter) / (cosInner - cosOuter), 0.0, 1.0)
                                      : (cosAngle >= cosOuter ? 1.0 : 0.0);
        s.radiance *= x * x * (3.0 - 2.0 * x);
    }
    return s;
}

// As blinnPhong(): E * (diffuse * T * N.L + specular * (N.H)^n), with the C++'s skip of the
// specular term for materials without one. `diffuse` is the material diffuse times the texture T
// (the G-buffer stores the product).
vec3 blinnPhong(vec3 normal, vec3 diffuse, vec3 specular, float exponent, vec3 toViewer, LightSample light) {
    float nl = dot(normal, light.toLight);
    if (nl <= 0.0) return vec3(0.0);
    vec3 c = diffuse * nl;
    if (specular != vec3(0.0)) {
        vec3 h = normalize(light.toLight + toViewer);
        c += specular * pow(max(dot(normal, h), 0.0), exponent);
    }
    return light.radiance * c;
}

// As unlitTerm(): emission + ambient * sceneAmbient * T (`ambient` is the material ambient
// times T, as the G-buffer stores it).
vec3 unlitTerm(vec3 emission, vec3 ambient, vec3 sceneAmbient) {
    return emission + ambient * sceneAmbient;
}

// As reflectDirection().
vec3 reflectDirection(vec3 d, vec3 n) { return d - 2.0 * dot(d, n) * n; }

// As refractDirection(): false on total internal reflection.
bool refractDirection(vec3 d, vec3 n, float eta, out vec3 refracted) {
    float cosi = -dot(d, n);
    float k = 1.0 - eta * eta * (1.0 - cosi * cosi);
    refracted = vec3(0.0);
    if (k < 0.0) return false;
    refracted = normalize(eta * d + (eta * cosi - sqrt(k)) * n);
    return true;
}

// As fresnelDielectric(): exact unpolarised Fresnel reflectance, 1 under total internal reflection.
float fresnelDielectric(float cosIncident, float n1, float n2) {
    float cosi = clamp(cosIncident, 0.0, 1.0);
    float sint2 = (n1 / n2) * (n1 / n2) * (1.0 - cosi * cosi);
    if (sint2 >= 1.0) return 1.0;
    float cost = sqrt(1.0 - sint2);
    float rs = (n1 * cosi - n2 * cost) / (n1 * cosi + n2 * cost);
    float rp = (n2 * cosi - n1 * cost) / (n2 * cosi + n1 * cost);
    return 0.5 * (rs * rs + rp * rp);
}

// As occluderTransmittance(): what one shadow-ray crossing of a surface lets through.
vec3 occluderTransmittance(bool castsShadows, float opacity, vec3 diffuse) {
    if (!castsShadows) return vec3(1.0);
    return (1.0 - opacity) * diffuse;
}

// As compose() with BlendRule::Design (walewski = false) or BlendRule::Walewski2019.
vec3 compose(float om, float orr, vec3 M, vec3 R, vec3 C, bool walewski) {
    vec3 cm = om * M + (1.0 - om) * (orr * R + (1.0 - orr) * C);
    if (!walewski) return cm;
    vec3 cr = orr * R + (1.0 - orr) * (om * M + (1.0 - om) * C);  // Walewski eq. (6)
    return 0.5 * (cm + cr);
}

// As uncomposeLocal(): the C that composes with M and R into `composite`; `fallback` where C's
// weight vanishes. Recovers the rasterizer's shadow-mapped C from its composed pixel.
vec3 uncomposeLocal(float om, float orr, vec3 M, vec3 R, vec3 composite, vec3 fallback, bool walewski) {
    float slope = (1.0 - om) * (1.0 - orr);
    if (slope < 1e-4) return fallback;
    return (composite - compose(om, orr, M, R, vec3(0.0), walewski)) / slope;
}

#endif
