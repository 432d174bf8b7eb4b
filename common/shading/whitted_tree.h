// The Whitted ray tree (Whitted 1980; Walewski 2019 Listing 8c with the composition of DESIGN.md),
// written once for both ray backends (shading_language.h): the walk over the tree, what a hit
// shades (its local colour over every light with shadow rays) and what it does with its reflected
// and refracted terms (the sky, its local colour, or a ray to trace, into which media).
//
// The tree is iterated with an explicit stack, not recursed: the device needs that (recursion
// through closest-hit shaders would need maxRayRecursionDepth >= max_depth + 2, and devices
// promise as little as 1), and one walk must serve both backends. Composition (composition.h
// compose()) is linear in the reflected, refracted and local terms, so each pending ray carries
// its throughput (its weight in the pixel's radiance) and a hit adds its weighted local term when
// popped. The importance cut-off (Walewski 2019 §3.3) looks at the product of weights along a path,
// which no traversal order changes: the walk traces exactly the rays a recursion traces, and sums
// their terms in another floating-point order (leaves' throughput x term, not nested compositions).
//
// What differs between the backends they provide, called as BACKEND_CALL(name)(...) and declared
// before this header is read (GLSL: functions; C++: members of a Backend class that the
// BACKEND_FUNCTIONs below take as their first argument, shading_language.h):
//   float traceRay(vec3 origin, vec3 direction)    a radiance ray's hit distance; < 0: a miss
//   Surface resolveHit()                           the surface the last traceRay hit
//   SurfaceMaterial surfaceMaterial(Surface s)
//   vec3 diffuseTexture(Surface s, float coneWidth, vec3 incoming)   T over the ray cone's footprint
//   int lightCount(); LightSample lightSample(int i, vec3 p); bool lightCastsShadows(int i)
//   vec3 shadowTransmittance(vec3 origin, vec3 direction, float distance, vec3 startAbsorption)
//   vec3 skyRadiance(vec3 direction)
//   float coneWidthAt(float width, float t)        a ray cone's width after t; 0 without ray cones
//   TreeSettings treeSettings()
//   MediumEntry mediumEntry(Surface s)              the medium stack's entry of s's object (medium_stack.h)
//   void countRay(int kind)                         kRayShadow ... kMediumError
// and the type Surface (position, geometricNormal, shadingNormal, object). GLSL reads whitted_tree_types.h
// (the walk's records, which the backend's functions use), then those functions, then this.
#ifndef WHITTED_TREE_H
#define WHITTED_TREE_H

#ifdef __cplusplus
#include <new>
#endif

#include "absorption.h"
#include "composition.h"
#include "direct_lighting.h"
#include "ray_geometry.h"
#include "shading_language.h"
#include "whitted_tree_types.h"

SHARED_BEGIN

#ifdef __cplusplus
// The walk's stack of pending rays, in C++ storage that is not constructed up front: 66 medium
// stacks set empty at every walk (a camera ray's) cost the reference a memset of 1 KB a pixel.
// An entry is copied in before it is read; PendingRay needs no destructor.
struct TreeStack {
    alignas(PendingRay) unsigned char bytes[kMaxTreeStack * sizeof(PendingRay)];
    PendingRay& at(int i) { return *std::launder(reinterpret_cast<PendingRay*>(bytes) + i); }
    void put(int i, const PendingRay& ray) { new (bytes + i * sizeof(PendingRay)) PendingRay(ray); }
};
#define TREE_STACK(name) TreeStack name
#define TREE_AT(name, i) name.at(i)
#define TREE_PUT(name, i, ray) name.put(i, ray)
// Inlined where called: called, their vec3 arguments and results pass through the stack in halves
// and reload as pairs, failed store-to-load forwardings that cost the walk about 7%.
#define TREE_INLINE __attribute__((always_inline))
#else
#define TREE_STACK(name) PendingRay name[kMaxTreeStack]
#define TREE_AT(name, i) name[i]
#define TREE_PUT(name, i, ray) name[i] = ray
#define TREE_INLINE
#endif

// The weights of M, R and C in compose(om, orr, M, R, C, walewski), which is linear in each:
// compose() of unit terms with its products by 0 left out (adding 0 changes no bit), scalar.
SHARED_FUNCTION vec3 compositionWeights(float om, float orr, bool walewski) {
    vec3 design = vec3(om, (1.0f - om) * orr, (1.0f - om) * (1.0f - orr));
    if (!walewski) return design;
    vec3 other = vec3((1.0f - orr) * om, orr, (1.0f - orr) * (1.0f - om));  // Walewski eq. (6)
    return 0.5f * (design + other);
}

// Where a hit's shadow rays start: just off the surface at `position`, on the side of its
// geometric normal `ng` that the ray arrives from (ArrivalSide). The Embree backend traces a
// block of first hits' shadow rays ahead, in packets, from here (first_hit_shadows.h).
SHARED_FUNCTION vec3 shadowRayOrigin(vec3 position, vec3 ng) {
    return offsetRayOrigin(position, ng);
}

// A light's unshadowed term `direct` at a hit, times the transmittance of its shadow ray where
// `shadowRays` and the light casts shadows (hard shadows, from `shadowOrigin` just off the surface
// on the viewer's side, in media of absorption `mediumAbsorption`).
BACKEND_FUNCTION TREE_INLINE vec3 shadowedLightTerm(BACKEND_PARAM vec3 direct, LightSample light, int index, bool shadowRays,
                                                    vec3 shadowOrigin, vec3 mediumAbsorption) {
    if (!shadowRays || !BACKEND_CALL(lightCastsShadows)(index)) return direct;
    BACKEND_CALL(countRay)(kRayShadow);
    return direct * BACKEND_CALL(shadowTransmittance)(shadowOrigin, light.toLight, light.distance, mediumAbsorption);
}

// The local colour C at a surface (direct_lighting.h): the unlit term, then every light's
// Blinn-Phong term, shadowed where `shadowRays` (shadowedLightTerm; `mediumAbsorption` of the
// media where the shadow rays start), summed in the lights' order. Lights facing away, or with
// the surface outside their spot cone, add nothing and trace no ray.
BACKEND_FUNCTION TREE_INLINE vec3 hitLocalColor(BACKEND_PARAM BACKEND_TYPE(Surface) s, SurfaceMaterial m, vec3 n, vec3 ng, vec3 toViewer,
                                    bool shadowRays, vec3 tex, vec3 mediumAbsorption) {
    vec3 c = unlitTerm(m.emission, m.ambient, BACKEND_CALL(treeSettings)().sceneAmbient, tex);
    vec3 shadowOrigin = shadowRayOrigin(s.position, ng);
    vec3 diffuse = m.diffuse * tex;
    int lights = BACKEND_CALL(lightCount)();
#if SHARED_LIGHT_BATCH > 1
    // In batches: the batch's unshadowed terms first, then their shadow rays, so that on the CPU
    // the lights' chains of square roots and divisions overlap instead of each waiting behind the
    // previous light's ray.
    for (int first = 0; first < lights; first += SHARED_LIGHT_BATCH) {
        int count = min(SHARED_LIGHT_BATCH, lights - first);
        LightSample samples[SHARED_LIGHT_BATCH];
        vec3 direct[SHARED_LIGHT_BATCH];
        for (int k = 0; k < count; ++k) {
            samples[k] = BACKEND_CALL(lightSample)(first + k, s.position);
            direct[k] = blinnPhong(n, diffuse, m.specular, m.specularExponent, toViewer, samples[k]);
        }
        for (int k = 0; k < count; ++k)
            if (direct[k] != vec3(0.0f))
                c += shadowedLightTerm(BACKEND_ARG direct[k], samples[k], first + k, shadowRays, shadowOrigin, mediumAbsorption);
    }
#else
    // One light at a time: lavapipe keeps even a one-light batch's arrays in memory (whitted-classic's
    // device trace took 2-5% longer).
    for (int i = 0; i < lights; ++i) {
        LightSample light = BACKEND_CALL(lightSample)(i, s.position);
        vec3 direct = blinnPhong(n, diffuse, m.specular, m.specularExponent, toViewer, light);
        if (direct != vec3(0.0f)) c += shadowedLightTerm(BACKEND_ARG direct, light, i, shadowRays, shadowOrigin, mediumAbsorption);
    }
#endif
    return c;
}

// A hit at `depth` with weight `importance` in the pixel, seen along unit `incoming`, its ray cone
// `coneWidth` wide there, in `media`: its local colour and its terms. `effects` (shadows,
// reflection, refraction) are traced at this hit (TracedEffects); with `localGiven`, `givenLocal`
// stands in for C (a hybrid's, shadowed by its maps). With `localIfWeighted`, C is shaded only where
// the composition weights it (composition.h localWeighs; 0 elsewhere). `wantsSky`: the environment
// terms are asked for (they are computed anyway for an effect not traced).
BACKEND_FUNCTION TREE_INLINE HitShading shadeHit(BACKEND_PARAM BACKEND_TYPE(Surface) s, SurfaceMaterial m, vec3 incoming, int depth, float importance,
                                     float coneWidth, MediumStack media, bvec3 effects, bool localGiven, vec3 givenLocal,
                                     bool localIfWeighted, bool wantsSky) {
    TreeSettings settings = BACKEND_CALL(treeSettings)();
    HitShading h;
    // Work on the side the ray arrives from.
    ArrivalSide side = arrivalSide(incoming, s.geometricNormal, s.shadingNormal, m.ior, settings.ambientIor);
    vec3 ng = side.geometricNormal, n = side.shadingNormal;
    HitScattering scattering = scatterAtHit(incoming, n, side.n1, side.n2, m.reflectivity, m.fresnel, m.opacity, depth, settings.maxDepth,
                                            settings.depthLimitLocal, importance, settings.importanceCutoff, effects.y, effects.z);
    h.reflectivity = scattering.reflectivity;
    h.transparency = scattering.transparency;
    h.composes = scattering.composes;
    h.tir = scattering.tir;
    if (localGiven) {
        h.local = givenLocal;
    } else if (!localIfWeighted || scattering.localWeighs) {
        h.local = hitLocalColor(BACKEND_ARG s, m, n, ng, -incoming, settings.shadows && effects.x,
                                BACKEND_CALL(diffuseTexture)(s, coneWidth, incoming), media.absorption);
    } else {
        h.local = vec3(0.0f);
    }
    h.reflected.traced = false;
    h.refracted.traced = false;
    h.reflected.value = vec3(0.0f);
    h.refracted.value = vec3(0.0f);
    h.skyReflected = h.local;
    h.skyRefracted = h.local;
    if (!scattering.tracesRays) return h;
    // The sky only where a term is asked for; a term of weight 0 keeps the local colour.
    if (scattering.weightM > 0.0f && (wantsSky || !effects.y)) h.skyReflected = BACKEND_CALL(skyRadiance)(scattering.reflectedDirection);
    if (scattering.weightR > 0.0f && (wantsSky || !effects.z)) h.skyRefracted = BACKEND_CALL(skyRadiance)(scattering.refractedDirection);
    if (h.tir) h.skyRefracted = h.skyReflected;

    h.reflected.value = h.local;
    if (!effects.y) {
        h.reflected.value = h.skyReflected;
    } else if (scattering.traceM) {
        h.reflected.traced = true;
        h.reflected.ray.origin = offsetRayOrigin(s.position, ng);
        h.reflected.ray.importance = importance * scattering.weightM;
        h.reflected.ray.direction = scattering.reflectedDirection;
        h.reflected.ray.depth = depth + 1;
        h.reflected.ray.throughput = vec3(1.0f);
        h.reflected.ray.coneWidth = coneWidth;
        h.reflected.ray.media = media;  // a reflected ray keeps its parent's media
    }
    h.refracted.value = h.local;
    if (h.tir) {
        h.refracted.value = h.reflected.value;
    } else if (!effects.z) {
        h.refracted.value = h.skyRefracted;
    } else if (scattering.traceR) {
        h.refracted.traced = true;
        h.refracted.ray.origin = offsetRayOrigin(s.position, -ng);
        h.refracted.ray.importance = importance * scattering.weightR;
        h.refracted.ray.direction = scattering.refractedDirection;
        h.refracted.ray.depth = depth + 1;
        h.refracted.ray.throughput = vec3(1.0f);
        h.refracted.ray.coneWidth = coneWidth;
        h.refracted.ray.media = media;
        // A refracted ray enters or leaves the hit's object (medium_stack.h).
        bool tracked = side.entering ? mediumEnter(h.refracted.ray.media, BACKEND_CALL(mediumEntry)(s))
                                     : mediumLeave(h.refracted.ray.media, s.object);
        if (!tracked) BACKEND_CALL(countRay)(kMediumError);
    }
    return h;
}

// The radiance along `root` and every ray it spawns, `root` traced first. The first hit traces
// `rootEffects` (TracedEffects); deeper hits trace everything.
BACKEND_FUNCTION TREE_INLINE vec3 traceTree(BACKEND_PARAM PendingRay root, bvec3 rootEffects) {
    TreeSettings settings = BACKEND_CALL(treeSettings)();
    TREE_STACK(stack);
    TREE_PUT(stack, 0, root);
    int top = 1;
    vec3 L = vec3(0.0f);
    while (top > 0) {
        --top;
        PendingRay ray = TREE_AT(stack, top);
        float t = BACKEND_CALL(traceRay)(ray.origin, ray.direction);
        if (t < 0.0f) {
            // Left the scene inside a closed object: an open mesh.
            if (ray.media.size > 0) BACKEND_CALL(countRay)(kMediumError);
            L += ray.throughput * BACKEND_CALL(skyRadiance)(ray.direction);
            continue;
        }
        BACKEND_TYPE(Surface) s = BACKEND_CALL(resolveHit)();
        // Beer-Lambert absorption of the media the segment ran through (medium_stack.h).
        vec3 throughput = mediumAbsorbs(ray.media.absorption) ? ray.throughput * segmentTransmittance(ray.media.absorption, t) : ray.throughput;
        HitShading h = shadeHit(BACKEND_ARG s, BACKEND_CALL(surfaceMaterial)(s), ray.direction, ray.depth, ray.importance,
                                BACKEND_CALL(coneWidthAt)(ray.coneWidth, t), ray.media, ray.depth == 0 ? rootEffects : bvec3(true), false,
                                vec3(0.0f), true, false);
        if (!h.composes) {
            L += throughput * h.local;
            continue;
        }
        // The composition's weights of M, R and C (compose() is linear in each).
        vec3 weights = compositionWeights(h.reflectivity, h.transparency, settings.walewski);
        float cM = weights.x, cR = weights.y, cC = weights.z;
        if (h.tir) {
            cM += cR;
            cR = 0.0f;
        }
        L += throughput * cC * h.local;
        if (cM > 0.0f) {
            if (h.reflected.traced) {
                BACKEND_CALL(countRay)(kRayReflection);
                TREE_PUT(stack, top, h.reflected.ray);
                TREE_AT(stack, top).throughput = throughput * cM;
                ++top;
            } else {
                L += throughput * cM * h.reflected.value;
            }
        }
        if (cR > 0.0f) {
            if (h.refracted.traced) {
                BACKEND_CALL(countRay)(kRayRefraction);
                TREE_PUT(stack, top, h.refracted.ray);
                TREE_AT(stack, top).throughput = throughput * cR;
                ++top;
            } else {
                L += throughput * cR * h.refracted.value;
            }
        }
    }
    return L;
}

SHARED_FUNCTION vec3 composedParts(HitParts p, bool walewski) {
    return p.composes ? compose(p.reflectivity, p.transparency, p.reflected, p.refracted, p.local, walewski) : p.local;
}

// shadeHit() at a surface a caller found (a G-buffer texel, a hybrid's hit), its secondary rays
// traced with the walk above.
BACKEND_FUNCTION TREE_INLINE HitParts shadeParts(BACKEND_PARAM BACKEND_TYPE(Surface) s, SurfaceMaterial m, vec3 incoming, int depth, float importance,
                                     float coneWidth, MediumStack media, bvec3 effects, bool localGiven, vec3 givenLocal,
                                     bool localIfWeighted, bool wantsSky) {
    HitShading h = shadeHit(BACKEND_ARG s, m, incoming, depth, importance, coneWidth, media, effects, localGiven, givenLocal,
                            localIfWeighted, wantsSky);
    HitParts p;
    p.local = h.local;
    p.reflectivity = h.reflectivity;
    p.transparency = h.transparency;
    p.composes = h.composes;
    p.skyReflected = h.skyReflected;
    p.skyRefracted = h.skyRefracted;
    // M, then R (under total internal reflection, M again), from one call site of the walk:
    // lavapipe compiles each inlined copy of its loop anew.
    p.reflected = h.reflected.value;
    p.refracted = h.refracted.value;
    for (int k = 0; k < 2; ++k) {
        HitTerm term = k == 0 ? h.reflected : h.refracted;
        vec3 v = k == 1 && h.tir ? p.reflected : term.value;
        if (term.traced) {
            BACKEND_CALL(countRay)(k == 0 ? kRayReflection : kRayRefraction);
            v = traceTree(BACKEND_ARG term.ray, bvec3(true));
        }
        if (k == 0) p.reflected = v;
        else p.refracted = v;
    }
    return p;
}

SHARED_END

#endif
