// Which texels ssr_fallback's ray-traced stage on the device shades, and what the others keep: read
// by its ray-generation shader (device_ssr_fallback.rgen) and by the classification pass of a
// compacted launch (ssr_classify.comp), which writes the texels it does not list in their stead.
#ifndef SSR_TEXELS_GLSL
#define SSR_TEXELS_GLSL

#include "device_gbuffer_inputs.glsl"
#include "ssr_texel.h"

// frame.rules.y: bit 0 shadows = "rt"; bits 1-2 fallback (0 rt, 1 sky, 2 none); bit 3 recursion =
// "single"; bit 4 glass = "ssr"; bit 5 ssr = false.
const uint kRayTracedShadows = 1u, kGlassSsr = 16u, kSingleRecursion = 8u, kSsrOff = 32u;

// Every texel starts as the lit image (the sky, and opaque matte texels shaded by the maps) with
// no terms for the composite; true where the ray-traced stage shades it (ssr_texel.h
// ssrStageShades: a reflective or refractive texel, or any texel with ray-traced shadows).
bool classifyTexel(ivec2 texel) {
    const int i = texelIndex(texel);
    for (int k = 0; k < kTexelRecords; ++k) texels[kTexelRecords * i + k] = vec4(0.0);
    radianceOut[i] = texelFetch(litImage, texel, 0);
    if (gbufferObject(texel) < 0) return false;
    return ssrStageShades(texelFetch(gOptical, texel, 0), (frame.rules.y & kRayTracedShadows) != 0u);
}

#endif
