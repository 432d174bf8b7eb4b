// ssr_fallback's ray-traced stage at one texel (de Macedo & Rodrigues §III, Figure 1), written once
// for its two ray backends (common/shading/shading_language.h): SsrFallbackTechnique's Embree path
// calls it with a class derived from EmbreeTreeBackend, device_ssr_fallback.rgen with the device's
// backend. Which texels the stage shades (ssrStageShades), which of their effects are ray traced
// (the whole texel, the fallback where SSR failed, the refraction, the shadows), the next bounce
// past an SSR hit that reflects or refracts, and the reflection's blend of SSR and the fallback.
// What stays with the callers: reading the texel into a surface and material, SSR's outputs and the
// G-buffer at SSR's hit (the backend functions below), counting, and writing the outputs; the seam
// blur and the composer follow the stage (seam_blur.h, ssr_composite.comp).
//
// The rules (above the shading) need nothing of the ray tree: ssr_texels.glsl reads them for the
// classification pass (ssr_classify.comp) too. The shading is read where the tree is
// (whitted_tree.h: C++, or a shader that read device_gbuffer_rays.glsl before this header).
#ifndef SSR_TEXEL_H
#define SSR_TEXEL_H

#ifdef __cplusplus
#include "common/shading/whitted_tree.h"
#else
#include "shading_language.h"
#endif

SHARED_BEGIN

// Where SSR fails (SsrFallbackTechnique::Fallback): ray tracing, the sky in the reflected
// direction, or no reflection.
const int kSsrFallbackRayTraced = 0;
const int kSsrFallbackSky = 1;
const int kSsrFallbackNone = 2;

// Where a texel's reflection comes from (ReflectionSource, seam_blur.h).
const int kReflectionNone = 0;
const int kReflectionSsr = 1;
const int kReflectionRayTraced = 2;
const int kReflectionSky = 3;
const int kReflectionMissing = 4;

// What the stage counts (countSsrTexel): a texel that traces rays, a fallback ray, a bounce past
// an SSR hit.
const int kSsrCountTraced = 0;
const int kSsrCountFallback = 1;
const int kSsrCountRecursion = 2;

// The G-buffer's optical target (reflectivity, ior, opacity, Fresnel flag): the surface reflects
// or refracts.
SHARED_FUNCTION bool reflectsOrRefracts(vec4 optical) { return optical.x > 0.0f || optical.w > 0.5f || optical.z < 1.0f; }

// Whether the stage shades a (non-sky) texel: a reflective or refractive one, or any with
// ray-traced shadows; the others keep the lit image (the maps' shadows).
SHARED_FUNCTION bool ssrStageShades(vec4 optical, bool rayTracedShadows) { return reflectsOrRefracts(optical) || rayTracedShadows; }

// The reflection's source for the seam blur: SSR's where its confidence is at least a half.
SHARED_FUNCTION int ssrReflectionSource(float confidence, int fallback) {
    return confidence >= 0.5f                  ? kReflectionSsr
           : fallback == kSsrFallbackRayTraced ? kReflectionRayTraced
           : fallback == kSsrFallbackSky       ? kReflectionSky
                                               : kReflectionMissing;
}

// The stage's settings.
struct SsrTexelPolicy {
    bool rayTracedShadows;  // shadows = "rt"
    bool ssrRefracts;       // glass = "ssr": SSR reflects off refractive texels, their refraction is traced
    int fallback;           // kSsrFallback*
    bool recursionTraced;   // recursion = "rt": an SSR hit that reflects or refracts has its next bounce traced
};

// The settings and whether SSR runs, as the one word the device reads (frame.rules.y): bit 0
// shadows = "rt"; bits 1-2 the fallback; bit 3 recursion = "single"; bit 4 glass = "ssr"; bit 5
// ssr = false.
const uint kSsrOptionRayTracedShadows = 1u;
const uint kSsrOptionSingleRecursion = 8u;
const uint kSsrOptionGlassSsr = 16u;
const uint kSsrOptionSsrOff = 32u;

SHARED_FUNCTION uint packSsrOptions(SsrTexelPolicy policy, bool ssrOn) {
    return (policy.rayTracedShadows ? kSsrOptionRayTracedShadows : 0u) | (uint(policy.fallback) << 1u) |
           (policy.recursionTraced ? 0u : kSsrOptionSingleRecursion) | (policy.ssrRefracts ? kSsrOptionGlassSsr : 0u) |
           (ssrOn ? 0u : kSsrOptionSsrOff);
}

SHARED_FUNCTION SsrTexelPolicy unpackSsrPolicy(uint options) {
    SsrTexelPolicy policy;
    policy.rayTracedShadows = (options & kSsrOptionRayTracedShadows) != 0u;
    policy.ssrRefracts = (options & kSsrOptionGlassSsr) != 0u;
    policy.fallback = int((options >> 1u) & 3u);
    policy.recursionTraced = (options & kSsrOptionSingleRecursion) == 0u;
    return policy;
}

SHARED_END

#endif

#if defined(__cplusplus) || defined(WHITTED_TREE_H)
#ifndef SSR_TEXEL_SHADING_H
#define SSR_TEXEL_SHADING_H

SHARED_BEGIN

// A shaded texel.
struct SsrTexelShading {
    HitParts parts;     // its terms (M: the fallback's, or the sky's)
    bool wholeTraced;   // refractive, ray traced whole as SSR does not refract (glass = "rt")
    bool refractive;
    bool composer;      // it takes part in the reflection composer with `reflection` as M; otherwise
                        // composedParts(parts) is its final colour
    vec3 reflection;    // M: SSR's and the fallback's, weighted by SSR's confidence
    int source;         // kReflection*
};

#ifndef __cplusplus
// What shadeSsrTexel asks of its backend besides the walk's (whitted_tree.h), defined by the shader
// (C++: members of the backend's class):
float ssrConfidence();       // SSR's confidence at the texel: 0 where it failed, did not run or is off
vec3 ssrHitColor();          // the lit image at SSR's hit (after ssrConfidence())
vec4 ssrHitOptical();        // the G-buffer's optical target at SSR's hit
vec3 loadSsrHit();           // reads SSR's hit texel as a surface; returns its position
Surface ssrHitSurface();     // that surface (after loadSsrHit())
SurfaceMaterial ssrHitMaterial();
vec3 texelFacingNormal();    // the texel's shading normal, facing the camera
void countSsrTexel(int kind);  // kSsrCount*
#endif

// The stage at a texel it shades (ssrStageShades) with G-buffer surface `s` of material `m` and
// optical target `optical`, seen along unit `incoming` with the camera ray's cone `coneWidth` wide
// there, in `media`; `lit`: the lit image's colour there (C with shadows from the maps). Two
// shadings at most, from one call site of the walk (lavapipe compiles each inlined copy of the ray
// tree anew): the texel's own, then, where SSR hit a surface that reflects or refracts, that
// surface's next bounce, ray traced and seen along the mirror ray (composed alone, as
// WhittedTracer::shade()).
BACKEND_FUNCTION SsrTexelShading shadeSsrTexel(BACKEND_PARAM BACKEND_TYPE(Surface) s, SurfaceMaterial m, vec4 optical, vec3 incoming,
                                               float coneWidth, MediumStack media, vec3 lit, SsrTexelPolicy policy) {
    SsrTexelShading r;
    r.refractive = optical.z < 1.0f;
    bool opaqueMatte = !reflectsOrRefracts(optical);
    // Refractive texels are ray traced whole, as SSR does not refract (unless glass = "ssr").
    r.wholeTraced = r.refractive && !policy.ssrRefracts;
    float confidence = r.wholeTraced ? 0.0f : BACKEND_CALL(ssrConfidence)();
    bool traceFallback = !r.wholeTraced && !opaqueMatte && confidence < 1.0f && policy.fallback == kSsrFallbackRayTraced;
    if (r.wholeTraced || traceFallback || policy.rayTracedShadows || r.refractive) BACKEND_CALL(countSsrTexel)(kSsrCountTraced);
    if (traceFallback) BACKEND_CALL(countSsrTexel)(kSsrCountFallback);
    // A refractive texel here (glass = "ssr") traces its refraction; its reflection is SSR's where
    // SSR resolved. The lit image's colour is C with shadows from the maps; with ray-traced shadows
    // C is shaded again.
    HitParts p;
    vec3 ssrM = vec3(0.0f);
    vec3 direction = incoming;
    int depth = 0;
    float importance = 1.0f;
    float cone = coneWidth;
    bvec3 effects = bvec3(policy.rayTracedShadows, r.wholeTraced || traceFallback, r.refractive);
    bool localGiven = !policy.rayTracedShadows;
    for (int pass = 0; pass < 2; ++pass) {
        HitParts q = shadeParts(BACKEND_ARG pass == 0 ? s : BACKEND_CALL(ssrHitSurface)(), pass == 0 ? m : BACKEND_CALL(ssrHitMaterial)(),
                                direction, depth, importance, cone, media, effects, localGiven, lit, pass == 1, false);
        if (pass == 1) {
            ssrM = composedParts(q, BACKEND_CALL(treeSettings)().walewski);
            break;
        }
        p = q;
        if (r.wholeTraced || !p.composes || confidence <= 0.0f) break;
        ssrM = BACKEND_CALL(ssrHitColor)();
        if (!policy.recursionTraced || !reflectsOrRefracts(BACKEND_CALL(ssrHitOptical)())) break;
        BACKEND_CALL(countSsrTexel)(kSsrCountRecursion);
        vec3 hitPosition = BACKEND_CALL(loadSsrHit)();
        direction = reflectDirection(incoming, BACKEND_CALL(texelFacingNormal)());
        // The camera ray's cone continued along the mirror ray to the hit.
        cone = BACKEND_CALL(coneWidthAt)(coneWidth, distance(s.position, hitPosition));
        depth = 1;
        importance = p.reflectivity;
        effects = bvec3(true);
        localGiven = false;
    }
    r.parts = p;
    r.composer = !r.wholeTraced && p.composes;
    r.reflection = vec3(0.0f);
    r.source = kReflectionNone;
    if (r.composer) {
        // The fallback's M: the traced ray, or (not traced) the sky in the reflected direction.
        vec3 fallbackM = policy.fallback == kSsrFallbackNone ? vec3(0.0f) : p.reflected;
        r.reflection = confidence * ssrM + (1.0f - confidence) * fallbackM;
        r.source = ssrReflectionSource(confidence, policy.fallback);
    }
    return r;
}

SHARED_END

#endif
#endif
