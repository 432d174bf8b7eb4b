// What every ray-tracing shader of the device backend (common/device_rays) shares: the scene's
// buffers, the payloads, and the ray types' shader-binding-table indices.
#ifndef DEVICE_RAYS_GLSL
#define DEVICE_RAYS_GLSL

#extension GL_EXT_ray_tracing : require
#extension GL_EXT_nonuniform_qualifier : require

#include "device_ray_records.h"

layout(set = 0, binding = 0) uniform accelerationStructureEXT topLevel;
layout(std140, set = 0, binding = 1) uniform Frame { DeviceFrame frame; };
layout(std430, set = 0, binding = 2) readonly buffer Materials { DeviceMaterial materials[]; };
layout(std430, set = 0, binding = 3) readonly buffer Lights { DeviceLight lights[]; };
layout(std430, set = 0, binding = 4) readonly buffer Instances { DeviceInstance instances[]; };
layout(std430, set = 0, binding = 5) readonly buffer Vertices { DeviceVertex vertices[]; };
layout(std430, set = 0, binding = 6) readonly buffer Indices { uint indices[]; };
// Rays by kind, counted on the device: primary, shadow, reflection, refraction (RayStats).
layout(std430, set = 0, binding = 7) buffer Counters { uint rayCounts[4]; };
layout(std430, set = 0, binding = 8) writeonly buffer Output { vec4 radianceOut[]; };
layout(set = 0, binding = 9) uniform sampler2DArray skyFaces;
layout(set = 0, binding = 10) uniform sampler2D sceneTextures[];
// Rays to replay (device_replay.rgen): frame.size.x of them, radiance rays first, then
// frame.size.y shadow rays.
layout(std430, set = 0, binding = 11) readonly buffer Replay { DeviceRay replayRays[]; };

// Radiance rays (hit group 0, miss 0) report their closest hit; the ray-generation shader shades it.
struct HitPayload {
    float t;         // < 0: missed
    uint instance;   // DeviceInstance index (the instance's custom index)
    uint primitive;
    vec2 barycentrics;
};

// Shadow rays (hit group 1, miss 1): the any-hit shader multiplies the transmittance of every
// transparent crossing (Walewski 2019 Listing 8b) and remembers the crossings, so that a ray
// through an edge shared by two triangles is attenuated once (as RayScene's shadowFilter).
const int kMaxCrossings = 16;
struct ShadowPayload {
    vec3 transmittance;
    uint missed;     // 1: nothing opaque stopped the ray
    int crossings;
    uint crossingInstance[kMaxCrossings];
    float crossingDistance[kMaxCrossings];
};

const uint kRadianceRay = 0u;
const uint kShadowRay = 1u;

#endif
