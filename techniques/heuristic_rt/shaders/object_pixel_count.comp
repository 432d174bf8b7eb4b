#version 460
// Visible pixels per object (Walewski 2019 §3.2's A) counted on the device from the G-buffer's
// object-id target, as visiblePixelsFromIds (common/raster/gbuffer.cpp): the host reads
// back a count an object instead of the target.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform usampler2D objectIds;  // object index + 1; 0 the sky
layout(std430, set = 0, binding = 1) buffer Counts { uint counts[]; };  // [0] the sky (and ids out of range), [o + 1] object o

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, textureSize(objectIds, 0)))) return;
    uint id = texelFetch(objectIds, texel, 0).r;
    atomicAdd(counts[id < uint(counts.length()) ? id : 0u], 1u);
}
