// The records of the Whitted ray tree's walk (whitted_tree.h), written once for both ray backends
// (shading_language.h); apart from the walk so that a shader can define its backend's functions,
// which use them, before it includes the walk. GLSL: include after the backend's medium entries
// (device_medium_stack.glsl).
#ifndef WHITTED_TREE_TYPES_H
#define WHITTED_TREE_TYPES_H

#include "medium_stack.h"
#include "shading_language.h"

SHARED_BEGIN

// The kinds of ray countRay() counts (RayStats' fields, the device's counters).
const int kRayShadow = 1;
const int kRayReflection = 2;
const int kRayRefraction = 3;
const int kMediumError = 4;

// A pop pushes at most two rays one level deeper: max_depth (at most 64) + 2 entries.
const int kMaxTreeStack = 66;

// What the tree reads of a hit's material.
struct SurfaceMaterial {
    vec3 emission, ambient, diffuse, specular;
    float specularExponent;
    float reflectivity;  // o_m, unless fresnel
    float ior;
    float opacity;       // 1 - o_r
    bool fresnel;
};

// The settings of a tree (WhittedSettings; the device frame's).
struct TreeSettings {
    int maxDepth;
    bool depthLimitLocal;    // DepthLimit::Local: C alone at the depth limit
    float importanceCutoff;
    bool walewski;           // BlendRule::Walewski2019
    bool shadows;            // shadow rays at all
    vec3 sceneAmbient;
    float ambientIor;
};

// A ray waiting to be traced. Its media last: hot fields first, and a C++ copy of the stack copies
// only the entries in use.
struct PendingRay {
    vec3 origin;
    float importance;  // its weight in the pixel, for the cut-off
    vec3 direction;
    int depth;         // of its hit: 0 for camera rays
    vec3 throughput;   // its radiance's weight in the pixel
    float coneWidth;   // ray cone at its origin (ray_cone.h)
    MediumStack media; // the media it travels in (medium_stack.h)
};

// A hit's reflected (M) or refracted (R) term: traced (a ray to follow), or a value in its place
// (the sky where the effect is not traced at this hit, C under the importance cut-off, 0 past the
// depth limit).
struct HitTerm {
    bool traced;
    vec3 value;
    PendingRay ray;  // when traced: its origin, direction, importance, depth, cone and media (throughput 1)
};

// One hit shaded up to its secondary rays.
struct HitShading {
    vec3 local;          // C
    float reflectivity;  // o_m (the Fresnel reflectance for dielectrics)
    float transparency;  // o_r
    bool composes;       // false: C alone
    bool tir;            // total internal reflection: R is M
    HitTerm reflected, refracted;
    vec3 skyReflected, skyRefracted;  // the rasterizer's environment terms, where asked for
};

// A hit's terms before composition (composedParts composes them): what the hybrids blend or
// substitute at their first hit.
struct HitParts {
    vec3 local, reflected, refracted;
    float reflectivity, transparency;
    bool composes;
    vec3 skyReflected, skyRefracted;
};

SHARED_END

#endif
