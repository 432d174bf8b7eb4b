// The records the ray-tracing shaders read (common/device_rays), declared once for C++ and GLSL:
// the C++ sees glm types in namespace hybridlab::device_rays and static_asserts their layout,
// GLSL reads them from std430 storage buffers and a std140 uniform. Only vec4-sized members, so
// std140, std430 and C++ agree without padding rules.
#ifndef DEVICE_RAY_RECORDS_H
#define DEVICE_RAY_RECORDS_H

// The lights buffer holds the lighting pass's records, LightData (shadow.x < 0: casts no shadow).
#ifdef __cplusplus
#include "common/raster/shaders/raster_records.h"
#else
#include "raster_records.h"
#endif

#ifdef __cplusplus
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace hybridlab::device_rays {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using raster_records::LightData;
#endif

// A Material (common/scene/material.h).
struct DeviceMaterial {
    vec4 emission;      // rgb
    vec4 ambient;       // rgb
    vec4 diffuse;       // rgb
    vec4 specular;      // rgb, a = Blinn-Phong exponent
    vec4 optical;       // x reflectivity, y IOR, z opacity, w fresnel (1 or 0)
    vec4 absorption;    // rgb per unit length inside; a = casts shadows (1 or 0)
    vec4 tilingOffset;  // xy texture tiling, zw texture offset
    ivec4 textures;     // x diffuse texture, y normal texture (-1: none)
};

// One instance of the top-level acceleration structure: one mesh of one object.
struct DeviceInstance {
    mat4 toWorld;       // object to world at the frame's time
    mat4 normalToWorld; // normalMatrix(toWorld) in the upper 3 x 3
    uvec4 geometry;     // x object, y mesh, z material, w first vertex in the vertex buffer
    uvec4 topology;     // x first index in the index buffer, y kHas* flags
};

// One vertex; the acceleration structures read the position (xyz of the first member).
struct DeviceVertex {
    vec4 positionU;     // xyz position, w texture u
    vec4 normalV;       // xyz normal, w texture v
    vec4 tangent;       // xyz tangent, w handedness
};

// Per frame: the camera, the sky and the Whitted settings (WhittedSettings, TracedEffects).
struct DeviceFrame {
    vec4 cameraPosition;  // xyz; w 1 perspective, 0 orthographic
    vec4 cameraRight;     // world offset of ndc.x = 1 (direction for perspective, position for orthographic)
    vec4 cameraUp;        // world offset of ndc.y = -1
    vec4 cameraForward;   // unit
    vec4 skyColor;        // rgb; a = 1 when the sky is a cube map
    vec4 ambient;         // rgb scene ambient; a = ambient IOR
    vec4 cone;            // x camera ray cone width, y its spread (ray_cone.h pixelCone)
    ivec4 size;           // x width, y height, z light count, w max depth
    vec4 settings;        // x importance cut-off, y Walewski blend (1 or 0), z shadows (1 or 0), w ray cones (1 or 0)
    uvec4 effects;        // traced at the first hit: x shadows, y reflection, z refraction (1 or 0)
    uvec4 rules;          // x depth_limit: 1 weighted, 0 local (DepthLimit); y the technique's flags;
                          // z 1: a compacted launch over TexelList's texels
};

// A ray to replay (benchmarks: the rays a frame traced, traced again on their own).
struct DeviceRay {
    vec4 originTmin;     // xyz origin, w tmin
    vec4 directionTmax;  // xyz unit direction, w tmax
};

// The head of a compacted launch's texel list (device_gbuffer_inputs.glsl TexelList): the launch's
// size as VkTraceRaysIndirectCommandKHR reads it, x the listed texels, y and z 1 (w unused).
struct TexelListHeader {
    uvec4 launch;
};

// A launch's counters: rays by kind, primary, shadow, reflection, refraction (RayStats' order),
// medium errors, then its invocations: those launched and those that traced a ray (what rays per
// invocation and a launch's idle invocations are read from).
#ifdef __cplusplus
inline constexpr unsigned kHasUvs = 1u, kHasTangents = 2u;
inline constexpr unsigned kLaunchedInvocations = 5u, kTracingInvocations = 6u, kRayCounterCount = 7u;
static_assert(sizeof(DeviceMaterial) == 128 && sizeof(DeviceInstance) == 160 && sizeof(DeviceVertex) == 48);
static_assert(sizeof(DeviceFrame) == 176 && sizeof(DeviceRay) == 32 && sizeof(TexelListHeader) == 16);
}  // namespace hybridlab::device_rays
#else
const uint kHasUvs = 1u, kHasTangents = 2u;
const uint kLaunchedInvocations = 5u, kTracingInvocations = 6u, kRayCounterCount = 7u;
#endif

#endif
