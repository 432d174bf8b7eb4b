// The media a ray travels in, written once for both ray backends (shading_language.h); Beer-Lambert
// absorption along a segment is absorption.h. The rule, the same for every tracer (the reference,
// the hybrids' traced rays, the two-term lens paths, the device's ray tree):
//
//   * A path starts in the ambient medium (nothing absorbs). A refracted ray that enters an object
//     through its front face pushes the object's entry; one that leaves through a back face pops
//     that object's entry, wherever it is in the stack (touching and overlapping objects). A
//     reflected ray keeps its parent's stack.
//   * A segment of length d carries exp(-A d), A the SUM of the absorption coefficients of every
//     medium in the stack (overlapping media add, as POV-Ray's media of nested hollow objects do;
//     a segment in an opaque object nested in a glass ball is inside the glass only).
//   * Eye-path segments are attenuated up to the surface they end on, whatever it is. A ray that
//     leaves the scene (the sky) is not attenuated: an unbounded segment inside a closed object
//     cannot happen, and an open one is not a medium.
//   * A shadow ray from a point inside the stack's media to a light at distance D carries
//     exp(-tau) with tau = A_start D + sum over crossings i of +-a_i (D - t_i): + where it enters
//     object i (front face), - where it leaves it (back face). That is the integral of A along
//     the ray whatever order the crossings come in (Embree reports them in any order); towards a
//     directional light (D infinite) tau = sum over crossings of -+a_i t_i (the light lies outside
//     every medium).
//   * A ray that leaves a medium it never entered (overlapping or open meshes), or enters more
//     than kMediumCapacity nested media, keeps its stack unchanged and is counted (RayStats::mediumErrors).
//
// Hakura & Snyder 2001's G (Kay & Greenberg's transparency) is this term along each lens path.
//
// An entry's layout is each backend's (MediumEntry, read by mediumEntryObject() and
// mediumEntryAbsorption()): on the CPU the object and its absorption; on the device the object and
// its material, 16 bits each, the absorption read from the material (device_medium_stack.glsl),
// since the device's walk keeps 66 pending rays with their stacks in the ray-tracing stack that
// NVIDIA's driver bounds (with the CPU's layout 48 pending rays took 14.6 KB an invocation and lost
// the device: H200, driver 580). GLSL defines MediumEntry and those two functions before this.
#ifndef MEDIUM_STACK_H
#define MEDIUM_STACK_H

#include "shading_language.h"

SHARED_BEGIN

#ifdef __cplusplus
struct MediumEntry {
    uint object;
    vec3 absorption;
};
inline uint mediumEntryObject(const MediumEntry& e) { return e.object; }
inline vec3 mediumEntryAbsorption(const MediumEntry& e) { return e.absorption; }
#endif

const int kMediumCapacity = 8;

struct MediumStack {
    MediumEntry entries[kMediumCapacity];  // innermost last; those past `size` are never read
    int size;
    vec3 absorption;  // the sum of the absorption coefficients of the media the ray is in
#ifdef __cplusplus
    // The ambient medium. A C++ copy copies only the entries in use: a camera ray's empty stack,
    // passed at every recursion, then costs its size and absorption alone.
    MediumStack() : size(0), absorption(0.0f) {}
    MediumStack(const MediumStack& other) : size(other.size), absorption(other.absorption) {
        for (int i = 0; i < size; ++i) entries[i] = other.entries[i];
    }
    MediumStack& operator=(const MediumStack& other) {
        size = other.size;
        absorption = other.absorption;
        for (int i = 0; i < size; ++i) entries[i] = other.entries[i];
        return *this;
    }
#endif
};

// The stack of a camera ray: nothing entered.
SHARED_FUNCTION MediumStack ambientMedium() {
    MediumStack s;
    s.size = 0;
    s.absorption = vec3(0.0f);
    return s;
}

SHARED_FUNCTION bool mediumAbsorbs(vec3 absorption) { return absorption.x > 0.0f || absorption.y > 0.0f || absorption.z > 0.0f; }

// The stack of a ray that entered the object of entry `e`; false (stack unchanged) when full.
SHARED_FUNCTION bool mediumEnter(INOUT_PARAM(MediumStack) s, MediumEntry e) {
    if (s.size == kMediumCapacity) return false;
    s.entries[s.size] = e;
    ++s.size;
    s.absorption += mediumEntryAbsorption(e);
    return true;
}

// The stack of a ray that left `object`; false (stack unchanged) when it was never entered.
SHARED_FUNCTION bool mediumLeave(INOUT_PARAM(MediumStack) s, uint object) {
    for (int i = s.size - 1; i >= 0; --i) {
        if (mediumEntryObject(s.entries[i]) != object) continue;
        for (int j = i; j + 1 < s.size; ++j) s.entries[j] = s.entries[j + 1];
        --s.size;
        s.absorption = vec3(0.0f);  // re-summed, so that no rounding accumulates along a path
        for (int j = 0; j < s.size; ++j) s.absorption += mediumEntryAbsorption(s.entries[j]);
        return true;
    }
    return false;
}

SHARED_END

#endif
