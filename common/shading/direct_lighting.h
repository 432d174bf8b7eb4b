// The local colour's terms (DESIGN.md "The shading model"), written once for both ray backends
// and the rasterizer's lighting pass (shading_language.h). All colours are linear.
//
// Local colour at a surface point P with shading normal N, view direction V (towards the eye):
//   C = emission + ambient * sceneAmbient * T
//       + sum over lights l of  vis_l * E_l * ( diffuse * T * max(N.L, 0)
//                                               + specular * max(N.H, 0)^exponent * [N.L > 0] )
// with T the diffuse texture (1 without one), L the unit direction to the light, H = norm(L + V),
// and E_l the light's radiance at P:
//   directional: colour * intensity
//   point:       colour * intensity / d^2
//   spot:        colour * intensity / d^2 * smoothstep(cos outer, cos inner, cos angle to axis)
// vis_l is the shadow transmittance (1 unshadowed; hard shadows; an occluder that casts shadows
// lets (1 - opacity) * diffuse through, its diffuse colour being its tint).
#ifndef DIRECT_LIGHTING_H
#define DIRECT_LIGHTING_H

#include "shading_language.h"

#ifdef __cplusplus
#include "common/raster/shaders/raster_records.h"
#else
#include "raster_records.h"  // kLight*
#endif

SHARED_BEGIN

#ifdef __cplusplus
using raster_records::kLightDirectional;
using raster_records::kLightPoint;
using raster_records::kLightSpot;
#endif

// Radiance arriving at a point from a light, ignoring shadows, and the unit direction towards it.
struct LightSample {
    vec3 radiance;
    vec3 toLight;    // unit
    float distance;  // to the light; infinity for directional lights
};

// The light of type `type` (kLight*) and radiance `colour * intensity` at `p`: inverse-square
// falloff for point and spot lights, and a spot's cone (the cosines of its inner and outer
// half-angles) faded by smoothstep, as POV-Ray's spotlight.
SHARED_FUNCTION LightSample sampleLight(uint type, vec3 radiance, vec3 position, vec3 direction, float cosInner, float cosOuter,
                                        vec3 p) {
    LightSample s;
    if (type == kLightDirectional) {
        s.toLight = -direction;
        s.distance = SHARED_INFINITY;
        s.radiance = radiance;
        return s;
    }
    vec3 d = position - p;
    float d2 = dot(d, d);
    s.distance = sqrt(d2);
    s.toLight = d / s.distance;
    s.radiance = radiance / d2;
    if (type == kLightSpot) {
        float cosAngle = dot(-s.toLight, direction);
        float x = cosInner > cosOuter ? clamp((cosAngle - cosOuter) / (cosInner - cosOuter), 0.0f, 1.0f)
                                      : (cosAngle >= cosOuter ? 1.0f : 0.0f);
        s.radiance *= x * x * (3.0f - 2.0f * x);
    }
    return s;
}

// One light's contribution, unshadowed: E * (diffuse * N.L + specular * (N.H)^n), `diffuse` the
// material's diffuse colour times its texture T. Most matte materials have no specular colour:
// the pow is skipped for them.
SHARED_FUNCTION vec3 blinnPhong(vec3 normal, vec3 diffuse, vec3 specular, float exponent, vec3 toViewer, LightSample light) {
    float nl = dot(normal, light.toLight);
    if (nl <= 0.0f) return vec3(0.0f);
    vec3 c = diffuse * nl;
    if (specular != vec3(0.0f)) {
        vec3 h = normalize(light.toLight + toViewer);
        c += specular * pow(max(dot(normal, h), 0.0f), exponent);
    }
    return light.radiance * c;
}

// emission + ambient * sceneAmbient * T: the part of C that needs no light (T = 1 where the
// ambient colour is already textured, as the G-buffer stores it).
SHARED_FUNCTION vec3 unlitTerm(vec3 emission, vec3 ambient, vec3 sceneAmbient, vec3 textureValue) {
    return emission + ambient * sceneAmbient * textureValue;
}

// What one shadow-ray crossing of a surface lets through.
SHARED_FUNCTION vec3 occluderTransmittance(bool castsShadows, float opacity, vec3 diffuse) {
    if (!castsShadows) return vec3(1.0f);
    return (1.0f - opacity) * diffuse;
}

// The level of detail of a diffuse texture of `width` x `height` texels, tiled `tiling` times, for
// a footprint of one uv unit: 0.5 log2 of the texels it covers (a ray cone's uv footprint adds to it).
SHARED_FUNCTION float textureUvUnitLod(float width, float height, vec2 tiling) {
    return 0.5f * log2(width * height * abs(tiling.x * tiling.y));
}

SHARED_END

#endif
