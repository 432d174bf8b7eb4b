#version 460
#extension GL_GOOGLE_include_directive : require
#include "device_rays.glsl"

layout(location = 1) rayPayloadInEXT ShadowPayload shadow;

void main() { shadow.missed = 1u; }
