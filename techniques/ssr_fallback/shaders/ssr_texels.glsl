// Which texels ssr_fallback's ray-traced stage on the device shades, and what the others keep: read
// by its ray-generation shader (device_ssr_fallback.rgen) and by the classification pass of a
// compacted launch (ssr_classify.comp), which writes the texels it does not list in their stead.
#ifndef SSR_TEXELS_GLSL
#define SSR_TEXELS_GLSL

#include "device_gbuffer_inputs.glsl"
#include "ssr_texel.h"

// Every texel starts as the lit image (the sky, and opaque matte texels shaded by the maps) with
// no terms for the composite; true where the ray-traced stage shades it (ssr_texel.h
// ssrStageShades: a reflective or refractive texel, or any texel with ray-traced shadows).
bool classifyTexel(ivec2 texel) {
    const int i = texelIndex(texel);
    for (int k = 0; k < kTexelRecords; ++k) texels[kTexelRecords * i + k] = vec4(0.0);
    radianceOut[i] = texelFetch(litImage, texel, 0);
    if (gbufferObject(texel) < 0) return false;
    return ssrStageShades(texelFetch(gOptical, texel, 0), (frame.rules.y & kSsrOptionRayTracedShadows) != 0u);
}

#endif
