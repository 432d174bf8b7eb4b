// The classification pass of a compacted launch (a compute shader over 8 x 8 texel tiles): each
// texel says whether it needs the ray-generation shader (the technique's classifyTexel()), and
// the listed texels are appended to the launch's list (device_gbuffer_inputs.glsl), whose first
// record is the indirect launch's size (vkCmdTraceRaysIndirectKHR), so that no invocation of the
// trace is launched only to return, as the tile classification of FidelityFX's hybrid
// reflections does. A tile's texels stay together
// in the list (one global atomic a tile): neighbours, whose rays are alike, share the device's
// SIMD lanes. The header's count was zeroed and its height and depth set to 1 before the pass.
#ifndef TEXEL_LIST_GLSL
#define TEXEL_LIST_GLSL

#include "device_gbuffer_inputs.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

shared uint tileListed, tileFirst;

// Called by every invocation of the workgroup (it holds barriers).
void listTexel(ivec2 texel, bool listed) {
    if (gl_LocalInvocationIndex == 0u) tileListed = 0u;
    barrier();
    const uint slot = listed ? atomicAdd(tileListed, 1u) : 0u;
    barrier();
    if (gl_LocalInvocationIndex == 0u && tileListed > 0u) tileFirst = atomicAdd(listHeader.launch.x, tileListed);
    barrier();
    if (listed) listedTexels[tileFirst + slot] = packTexel(texel);
}

// The technique's classification, included before this file: true where the texel needs the
// ray-generation shader; where not, it writes the texel's outputs itself.
bool classifyTexel(ivec2 texel);

void main() {
    const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    listTexel(texel, all(lessThan(texel, frame.size.xy)) && classifyTexel(texel));
}

#endif
