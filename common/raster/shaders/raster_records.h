// What the raster core's shaders (scene_data.glsl's geometry passes, shading.glsl, the deferred
// lighting pass) and its C++ (GpuScene, ShadowMaps, DeferredLighting) exchange, declared once for
// C++ and GLSL (as device_ray_records.h): the C++ sees glm types in namespace
// hybridlab::raster_records and static_asserts their layout. Only mat4 and vec4-sized members, and
// the push constants' two uints after their mat4, so std140, std430 and C++ agree without padding rules.
#ifndef RASTER_RECORDS_H
#define RASTER_RECORDS_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace hybridlab::raster_records {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = std::uint32_t;
#define RASTER_CONSTANT inline constexpr
#else
#define RASTER_CONSTANT const
#endif

// One drawn object at the frame's time.
struct ObjectData {
    mat4 model;         // object to world at the frame's time
    mat4 normalMatrix;  // inverse transpose of the upper 3x3 (normalMatrix() in transform.h)
};

// A Material (common/scene/material.h).
struct MaterialData {
    vec4 emission;      // rgb
    vec4 ambient;       // rgb
    vec4 diffuse;       // rgb
    vec4 specular;      // rgb, a = Blinn-Phong exponent
    vec4 optical;       // reflectivity, IOR, opacity, fresnel (1 or 0)
    vec4 tilingOffset;  // xy texture tiling, zw texture offset
    ivec4 textures;     // x diffuse texture, y normal texture (-1: none)
};

// One draw's object and material (a record of the dynamic uniform buffer, bound at the draw's offset).
struct DrawRecord {
    ObjectData object;
    MaterialData material;
};

// Push constants of the geometry passes: the camera's (or light's) view-projection, and what is drawn.
struct DrawConstants {
    mat4 viewProj;
    uint object;
    uint flags;  // kHasTangentSpace
};
RASTER_CONSTANT uint kHasTangentSpace = 1u;  // the mesh has uvs and tangents (normal mapping possible)

// A light as the lighting pass sees it (shading.glsl; filled in deferred_lighting.cpp).
RASTER_CONSTANT uint kLightDirectional = 0u;
RASTER_CONSTANT uint kLightPoint = 1u;
RASTER_CONSTANT uint kLightSpot = 2u;
struct LightData {
    vec4 radiance;   // rgb = colour * intensity, a = type (kLight*)
    vec4 position;   // xyz (point, spot), w = cos of the inner cone half-angle (spotCone())
    vec4 direction;  // xyz the way the light travels (unit), w = cos of the outer cone half-angle
    ivec4 shadow;    // x first shadow-map layer (-1: casts no shadow), y its layer count (1, or 6 for a cube)
};

// One layer of the shadow-map array.
struct ShadowLayer {
    mat4 viewProj;  // world to the light's clip space (y down, reverse-Z)
    vec4 params;    // x world size of a texel (at unit distance when y = 1: perspective)
};

// The deferred lighting pass's per-frame uniforms.
struct FrameUniforms {
    vec4 cameraPosition;  // xyz; w 1 perspective, 0 orthographic
    vec4 cameraRight;     // right * tan(fovY / 2) * aspect (perspective) or * half width (orthographic)
    vec4 cameraUp;        // up * tan(fovY / 2) or * half height
    vec4 cameraForward;
    vec4 sceneAmbient;    // rgb; a = ambient IOR
    vec4 skyColor;        // rgb
    uvec4 counts;         // x lights, z width, w height
    vec4 shadowParams;    // x PCF radius (texels), y normal offset (texels)
};

#ifdef __cplusplus
static_assert(sizeof(ObjectData) == 128 && sizeof(MaterialData) == 112 && sizeof(DrawRecord) == 240);
static_assert(sizeof(DrawConstants) == 72 && offsetof(DrawConstants, object) == 64 && offsetof(DrawConstants, flags) == 68);
static_assert(sizeof(LightData) == 64 && sizeof(ShadowLayer) == 80 && sizeof(FrameUniforms) == 128);
}  // namespace hybridlab::raster_records
#endif
#undef RASTER_CONSTANT

#endif
