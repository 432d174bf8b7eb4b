// heuristic_rt's trace at one texel of a selected object (Walewski 2019 Listings 8a-8d), written
// once for its two ray backends (common/shading/shading_language.h): HeuristicRtTechnique's Embree
// path calls it with a class derived from EmbreeTreeBackend, device_heuristic_rt.rgen with the
// device's backend (device_gbuffer_rays.glsl, read before this header). What stays with the
// callers: reading the texel into a surface and material, the P-buffer's colour, and writing the
// terms and their blend (composedParts(), whitted_tree.h: Listing 10).
#ifndef HEURISTIC_TEXEL_H
#define HEURISTIC_TEXEL_H

#ifdef __cplusplus
#include "common/shading/whitted_tree.h"
#endif

SHARED_BEGIN

// Bits of a texel's selected effects: 1 << Effect (heuristic.h), as the selection sends them down.
const uint kSelectedShadows = 1u;
const uint kSelectedReflection = 2u;
const uint kSelectedRefraction = 4u;

// The effects the selection's bits trace (TracedEffects: shadows, reflection, refraction).
SHARED_FUNCTION bvec3 selectedTracedEffects(uint bits) {
    return bvec3((bits & kSelectedShadows) != 0u, (bits & kSelectedReflection) != 0u, (bits & kSelectedRefraction) != 0u);
}

// The terms of a texel whose object's effects `selected` (bits above) are traced, seen along unit
// `incoming` with the camera ray's cone `coneWidth` wide there, in `media`, from the G-buffer's
// surface `s` of material `m`. `rasterPBuffer`: the P-buffer `pbuffer` is the rasterizer's lighting
// pass (lighting = "raster"), so where shadows are not selected the texel keeps its local colour,
// shadowed by the maps (or not at all): recovered from its composition with the sky terms the pass
// used (composition.h uncomposeLocal). Otherwise (lighting = "cpu") the local colour is shaded here,
// with shadow rays where shadows are selected or `unselectedShadowRays` (raster_shadows = "rays",
// which only lighting = "cpu" takes).
BACKEND_FUNCTION HitParts heuristicTexelParts(BACKEND_PARAM BACKEND_TYPE(Surface) s, SurfaceMaterial m, vec3 incoming, float coneWidth,
                                              MediumStack media, uint selected, bool rasterPBuffer, bool unselectedShadowRays,
                                              vec3 pbuffer) {
    bvec3 effects = selectedTracedEffects(selected);
    bool localFromPBuffer = !effects.x && rasterPBuffer;
    effects.x = effects.x || unselectedShadowRays;
    HitParts p = shadeParts(BACKEND_ARG s, m, incoming, 0, 1.0f, coneWidth, media, effects, false, vec3(0.0f), false, localFromPBuffer);
    if (localFromPBuffer) {
        // The sky terms where the texel traces rays; at max_depth 0 it traces none and composes
        // M = R = 0 (the truncated tree), which the recovered colour composes back to the P-buffer.
        TreeSettings settings = BACKEND_CALL(treeSettings)();
        bool sky = settings.maxDepth > 0;
        p.local = p.composes ? uncomposeLocal(p.reflectivity, p.transparency, sky ? p.skyReflected : vec3(0.0f),
                                              sky ? p.skyRefracted : vec3(0.0f), pbuffer, p.local, settings.walewski)
                             : pbuffer;
    }
    return p;
}

SHARED_END

#endif
