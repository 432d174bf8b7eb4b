#version 460
// heuristic_rt's classification pass for the compacted trace (texel_list.glsl): the texels of
// selected objects are listed for device_heuristic_rt.rgen; the others keep the P-buffer here.
#extension GL_GOOGLE_include_directive : require
#include "heuristic_texels.glsl"
#include "texel_list.glsl"
