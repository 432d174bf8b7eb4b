#version 460
// ssr_fallback's classification pass for the compacted trace (texel_list.glsl): the texels its
// ray-traced stage shades are listed for device_ssr_fallback.rgen; the others keep the lit image here.
#extension GL_GOOGLE_include_directive : require
#include "ssr_texels.glsl"
#include "texel_list.glsl"
