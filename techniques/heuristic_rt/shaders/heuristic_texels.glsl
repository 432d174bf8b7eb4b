// Which texels heuristic_rt's ray stage on the device traces, and what the others keep: read by
// its ray-generation shader (device_heuristic_rt.rgen) and by the classification pass of a
// compacted launch (heuristic_classify.comp), which writes the untraced texels in its stead.
#ifndef HEURISTIC_TEXELS_GLSL
#define HEURISTIC_TEXELS_GLSL

#include "device_gbuffer_inputs.glsl"

// The effects selected for the texel's object, as bits (heuristic_texel.h: 1 << Effect, heuristic.h;
// 0: the sky, or an object the selection left out).
uint selectedEffects(ivec2 texel) {
    const int object = gbufferObject(texel);
    return object < 0 ? 0u : objectData[object];
}

// Whether the texel is traced; a texel of an object left out keeps the P-buffer (the lit image),
// written here, and with debug images (frame.rules.y) records the mask 0 and no traced terms.
bool classifyTexel(ivec2 texel) {
    if (selectedEffects(texel) != 0u) return true;
    const int i = texelIndex(texel);
    radianceOut[i] = texelFetch(litImage, texel, 0);
    if (frame.rules.y != 0u)
        for (int k = 0; k < kTexelRecords; ++k) texels[kTexelRecords * i + k] = vec4(0.0, 0.0, 0.0, k == 0 ? 1.0 : 0.0);
    return false;
}

#endif
