// What every ray-tracing shader of the device backend (common/device_rays) shares: the scene's
// buffers (with device_frame.glsl's frame, counters and output), the payloads, and the ray types'
// shader-binding-table indices.
#ifndef DEVICE_RAYS_GLSL
#define DEVICE_RAYS_GLSL

#extension GL_EXT_ray_tracing : require
#extension GL_EXT_nonuniform_qualifier : require

#include "device_frame.glsl"

layout(set = 0, binding = 0) uniform accelerationStructureEXT topLevel;
layout(std430, set = 0, binding = 2) readonly buffer Materials { DeviceMaterial materials[]; };
layout(std430, set = 0, binding = 3) readonly buffer Lights { LightData lights[]; };
layout(std430, set = 0, binding = 4) readonly buffer Instances { DeviceInstance instances[]; };
layout(std430, set = 0, binding = 5) readonly buffer Vertices { DeviceVertex vertices[]; };
layout(std430, set = 0, binding = 6) readonly buffer Indices { uint indices[]; };
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
// transparent crossing (Walewski 2019 Listing 8b), sums the optical depth of the absorbing ones
// (device_medium_stack.glsl) and remembers the crossings, so that a ray through an edge shared by
// two triangles is attenuated once (as RayScene's shadowFilter).
const int kMaxCrossings = 16;
struct ShadowPayload {
    vec3 transmittance;
    uint missed;     // 1: nothing opaque stopped the ray
    vec3 opticalDepth;
    float lightDistance;  // D; < 0: a directional light (infinitely far)
    int crossings;
    uint crossingInstance[kMaxCrossings];
    float crossingDistance[kMaxCrossings];
};

// The geometric normal of a triangle of an instance, in world space, following the winding: the
// closest-hit path's and the shadow any-hit's (SurfaceHit::geometricNormal).
vec3 triangleGeometricNormal(uint instance, uint primitive) {
    DeviceInstance inst = instances[instance];
    uint first = inst.topology.x + 3u * primitive;
    uint base = inst.geometry.w;
    mat4 M = inst.toWorld;
    vec3 p0 = (M * vec4(vertices[base + indices[first]].positionU.xyz, 1.0)).xyz;
    vec3 p1 = (M * vec4(vertices[base + indices[first + 1u]].positionU.xyz, 1.0)).xyz;
    vec3 p2 = (M * vec4(vertices[base + indices[first + 2u]].positionU.xyz, 1.0)).xyz;
    return normalize(cross(p1 - p0, p2 - p0));
}

// The camera ray through the centre of `pixel`, as Camera::rayThroughNdc (deviceFrame's camera
// vectors): from the eye (perspective) or from the pixel on the view plane (orthographic).
void cameraRay(ivec2 pixel, out vec3 origin, out vec3 direction) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(frame.size.xy) * 2.0 - 1.0;
    if (frame.cameraPosition.w != 0.0) {
        origin = frame.cameraPosition.xyz;
        direction = normalize(ndc.x * frame.cameraRight.xyz + ndc.y * frame.cameraUp.xyz + frame.cameraForward.xyz);
    } else {
        origin = frame.cameraPosition.xyz + ndc.x * frame.cameraRight.xyz + ndc.y * frame.cameraUp.xyz;
        direction = frame.cameraForward.xyz;
    }
}

const uint kRadianceRay = 0u;
const uint kShadowRay = 1u;

#endif
