// The media a device ray travels in: MediumStack (common/raytrace/medium_stack.h, which states
// the rule) on the device; Beer-Lambert absorption along a segment is common/shading/absorption.h,
// written once for both backends. The stack's push and pop mirror the C++'s few lines (change
// both together) because its entries differ: here an entry is the object and its material, 16
// bits each, the absorption read from the material. A pending ray carries its stack (PendingRay,
// common/shading/whitted_tree_types.h), and the walk's stack of pending rays lives in the
// ray-tracing stack, which NVIDIA's driver bounds: with the C++'s layout (a vec3
// an entry) 48 pending rays took 14.6 KB an invocation and lost the device (H200, driver 580; 32
// took 10 KB and ran); the walk holds 66 (RayStackBudget tests the bound).
// Include after device_rays.glsl (the materials).
#ifndef DEVICE_MEDIUM_STACK_GLSL
#define DEVICE_MEDIUM_STACK_GLSL

#include "absorption.h"

const int kMediumCapacity = 8;  // MediumStack::kCapacity

// The material of a surface that absorbs nothing inside (the G-buffer's, device_gbuffer_rays.glsl).
const uint kNoAbsorption = 0xFFFFu;
vec3 mediumAbsorption(uint material) { return material == kNoAbsorption ? vec3(0.0) : materials[material].absorption.rgb; }

struct MediumStack {
    uint entries[kMediumCapacity];  // object | material << 16 (DeviceRayScene keeps both below 0xFFFF)
    int size;
    vec3 absorption;  // sum of the absorption coefficients of the media the ray is in
};

MediumStack ambientMedium() {
    MediumStack s;
    for (int i = 0; i < kMediumCapacity; ++i) s.entries[i] = 0u;
    s.size = 0;
    s.absorption = vec3(0.0);
    return s;
}

bool mediumAbsorbs(MediumStack s) { return s.absorption.x > 0.0 || s.absorption.y > 0.0 || s.absorption.z > 0.0; }

// The stack of a ray that entered `object` of `material`; false (stack unchanged) when full.
bool mediumEnter(inout MediumStack s, uint object, uint material) {
    if (s.size == kMediumCapacity) return false;
    s.entries[s.size] = object | (material << 16);
    ++s.size;
    s.absorption += mediumAbsorption(material);
    return true;
}

// The stack of a ray that left `object`; false (stack unchanged) when it was never entered.
bool mediumLeave(inout MediumStack s, uint object) {
    for (int i = s.size - 1; i >= 0; --i) {
        if ((s.entries[i] & 0xFFFFu) != object) continue;
        for (int j = i; j + 1 < s.size; ++j) s.entries[j] = s.entries[j + 1];
        --s.size;
        s.absorption = vec3(0.0);  // re-summed, so that no rounding accumulates along a path
        for (int j = 0; j < s.size; ++j) s.absorption += mediumAbsorption(s.entries[j] >> 16);
        return true;
    }
    return false;
}

#endif
