#version 460
#extension GL_GOOGLE_include_directive : require
#include "device_rays.glsl"

layout(location = 0) rayPayloadInEXT HitPayload hit;

void main() { hit.t = -1.0; }
