// The media a device ray travels in and Beer-Lambert absorption along it: in GLSL,
// MediumStack and segmentTransmittance (common/raytrace/medium_stack.h), which states the rule.
// These few lines mirror that header line by line; change both together.
#ifndef DEVICE_MEDIUM_STACK_GLSL
#define DEVICE_MEDIUM_STACK_GLSL

const int kMediumCapacity = 8;  // MediumStack::kCapacity

struct MediumStack {
    uint objects[kMediumCapacity];
    vec3 absorptions[kMediumCapacity];
    int size;
    vec3 absorption;  // sum of the absorption coefficients of the media the ray is in
};

MediumStack ambientMedium() {
    MediumStack s;
    for (int i = 0; i < kMediumCapacity; ++i) {
        s.objects[i] = 0u;
        s.absorptions[i] = vec3(0.0);
    }
    s.size = 0;
    s.absorption = vec3(0.0);
    return s;
}

bool mediumAbsorbs(MediumStack s) { return s.absorption.x > 0.0 || s.absorption.y > 0.0 || s.absorption.z > 0.0; }

// The stack of a ray that entered `object` (absorption `a`); false (stack unchanged) when full.
bool mediumEnter(inout MediumStack s, uint object, vec3 a) {
    if (s.size == kMediumCapacity) return false;
    s.objects[s.size] = object;
    s.absorptions[s.size] = a;
    ++s.size;
    s.absorption += a;
    return true;
}

// The stack of a ray that left `object`; false (stack unchanged) when it was never entered.
bool mediumLeave(inout MediumStack s, uint object) {
    for (int i = s.size - 1; i >= 0; --i) {
        if (s.objects[i] != object) continue;
        for (int j = i; j + 1 < s.size; ++j) {
            s.objects[j] = s.objects[j + 1];
            s.absorptions[j] = s.absorptions[j + 1];
        }
        --s.size;
        s.absorption = vec3(0.0);  // re-summed, so that no rounding accumulates along a path
        for (int j = 0; j < s.size; ++j) s.absorption += s.absorptions[j];
        return true;
    }
    return false;
}

// Beer-Lambert transmittance of a segment of `len` in media of total absorption `a`. Exactly 1
// for a = 0 (also for an infinite length, where exp(-0 * inf) would be NaN).
vec3 segmentTransmittance(vec3 a, float len) {
    vec3 t = vec3(1.0);
    for (int c = 0; c < 3; ++c)
        if (a[c] > 0.0) t[c] = exp(-a[c] * len);
    return t;
}

// A shadow ray's optical depth gained at an absorbing crossing at distance t: +-a (D - t) towards
// a light at distance D, entering (+) or leaving (-); -+a t towards a directional light (D < 0
// here: infinite), which lies outside every medium (medium_stack.h, RayScene's shadowFilter).
vec3 crossingOpticalDepth(vec3 a, bool entering, float t, float D) {
    if (D >= 0.0) return (entering ? 1.0 : -1.0) * a * (D - t);
    return (entering ? -1.0 : 1.0) * a * t;
}

#endif
