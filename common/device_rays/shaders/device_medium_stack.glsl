// The device's entries of the medium stack (common/shading/medium_stack.h, which states the rule and
// keeps the stack for both backends): an entry is the object and its material, 16 bits each
// (DeviceRayScene keeps both below 0xFFFF), the absorption read from the material. The walk's
// stack of pending rays, each with its media, lives in the ray-tracing stack, which NVIDIA's driver
// bounds (RayStackBudget tests the bound).
// Include after device_rays.glsl (the materials).
#ifndef DEVICE_MEDIUM_STACK_GLSL
#define DEVICE_MEDIUM_STACK_GLSL

// The material of a surface that absorbs nothing inside (the G-buffer's, device_gbuffer_rays.glsl).
const uint kNoAbsorption = 0xFFFFu;
vec3 mediumAbsorption(uint material) { return material == kNoAbsorption ? vec3(0.0) : materials[material].absorption.rgb; }

#define MediumEntry uint
uint mediumEntryObject(uint e) { return e & 0xFFFFu; }
vec3 mediumEntryAbsorption(uint e) { return mediumAbsorption(e >> 16); }

#include "absorption.h"
#include "medium_stack.h"

#endif
