#version 460
// The hierarchical depth of the SSR pass's "hiz" traversal (FidelityFX SSSR; Uludag, GPU Pro 5):
// level 0 holds the view depth of every G-buffer texel (sky: far), each further level the nearest
// (minimum) depth of the 2 x 2 texels below it, and of the extra row or column when the level
// below has an odd size, so that a cell never hides a nearer texel. Level 0 also lists the texels
// ssr_trace.comp marches (reflective, opaque unless the uniforms ask for refractive ones too), so that
// it runs on those alone: lavapipe executes every instruction of a shader for a group of lanes
// while any lane is live, so a full-screen dispatch pays the march's set-up for every texel.
#extension GL_GOOGLE_include_directive : require
#include "ssr_records.h"

layout(local_size_x = kSsrPyramidGroupSize, local_size_y = kSsrPyramidGroupSize) in;

layout(constant_id = 0) const bool kFromGBuffer = false;  // level 0

layout(std140, set = 0, binding = 0) uniform Uniforms { PyramidUniforms u; };
layout(set = 0, binding = 1) uniform sampler2D gPosition;
layout(set = 0, binding = 2) uniform usampler2D gObjectId;
layout(set = 0, binding = 3, r32f) uniform readonly image2D finer;  // the level below (unused for level 0)
layout(set = 0, binding = 4, r32f) uniform writeonly image2D level;
layout(set = 0, binding = 5) uniform sampler2D gOptical;
// The texels to march, packed x | y << 16, and the indirect dispatch that marches them.
layout(std430, set = 0, binding = 6) buffer MarchList {
    MarchListHeader header;
    uint texels[];
} marchList;

const float kSkyDepth = 1e30;

void main() {
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(level);
    if (cell.x >= size.x || cell.y >= size.y) return;
    if (kFromGBuffer) {
        bool sky = texelFetch(gObjectId, cell, 0).r == 0u;
        float d = sky ? kSkyDepth : -(u.view * vec4(texelFetch(gPosition, cell, 0).xyz, 1.0)).z;
        imageStore(level, cell, vec4(d));
        vec4 optical = texelFetch(gOptical, cell, 0);  // reflectivity, IOR, opacity, fresnel
        bool reflective = optical.x > 0.0 || optical.w > 0.5;
        // SSR does not refract: refractive texels are ray traced, their reflection too unless flags.x asks for it.
        if (!sky && reflective && (optical.z >= 1.0 || u.flags.x > 0.5)) {
            uint i = atomicAdd(marchList.header.count, 1u);
            marchList.texels[i] = uint(cell.x) | (uint(cell.y) << 16);
            atomicMax(marchList.header.groups[0], i / kSsrMarchGroupSize + 1u);
        }
        return;
    }
    ivec2 below = imageSize(finer);
    // Texels 2c and 2c + 1 of the finer level, and 2c + 2 where this is its last cell and the finer size is odd.
    ivec2 last = min(2 * cell + 1 + ivec2(cell.x == size.x - 1 ? below.x & 1 : 0, cell.y == size.y - 1 ? below.y & 1 : 0), below - 1);
    float d = kSkyDepth;
    for (int y = 2 * cell.y; y <= last.y; ++y)
        for (int x = 2 * cell.x; x <= last.x; ++x) d = min(d, imageLoad(finer, ivec2(x, y)).r);
    imageStore(level, cell, vec4(d));
}
