// The one shading model (DESIGN.md "The shading model") for the shaders: the physics is written
// once for C++ and GLSL in common/shading (direct_lighting.h, reflection_refraction.h,
// composition.h), which this file includes; here only what reads the shaders' own records.
#ifndef SHADING_GLSL
#define SHADING_GLSL

#include "cube_map.glsl"

#include "composition.h"
#include "direct_lighting.h"
#include "raster_records.h"  // LightData, kLight*
#include "reflection_refraction.h"

// The light of record `light` at p, ignoring shadows (sampleLight on LightData's packing).
LightSample sampleLightRecord(LightData light, vec3 p) {
    return sampleLight(uint(light.radiance.a), light.radiance.rgb, light.position.xyz, light.direction.xyz, light.position.w,
                       light.direction.w, p);
}

#endif
