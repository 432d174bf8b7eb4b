#version 460
// Closest hit of a radiance ray: where, on what. The ray-generation shader resolves and shades it
// (the recursion lives there, whitted.rgen).
#extension GL_GOOGLE_include_directive : require
#include "device_rays.glsl"

layout(location = 0) rayPayloadInEXT HitPayload hit;
hitAttributeEXT vec2 barycentrics;

void main() {
    hit.t = gl_HitTEXT;
    hit.instance = uint(gl_InstanceCustomIndexEXT);
    hit.primitive = uint(gl_PrimitiveID);
    hit.barycentrics = barycentrics;
}
