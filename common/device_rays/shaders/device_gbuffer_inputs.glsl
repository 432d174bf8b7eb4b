// The inputs of the hybrids' ray stage on the device (set 1 of DeviceGBufferTracer,
// common/device_rays/device_gbuffer_tracer.h): the rasterizer's targets and lit image, the
// technique's per-object data, SSR's outputs, the per-texel records, the technique's counters and
// the compacted launch's texel list. Without the ray-tracing extension, so that the classification
// passes read them as the ray-generation shaders do (device_gbuffer_rays.glsl).
#ifndef DEVICE_GBUFFER_INPUTS_GLSL
#define DEVICE_GBUFFER_INPUTS_GLSL

#include "device_frame.glsl"

layout(set = 1, binding = 0) uniform sampler2D gPosition;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gEmission;
layout(set = 1, binding = 3) uniform sampler2D gAmbient;
layout(set = 1, binding = 4) uniform sampler2D gDiffuse;
layout(set = 1, binding = 5) uniform sampler2D gSpecular;
layout(set = 1, binding = 6) uniform sampler2D gOptical;
layout(set = 1, binding = 7) uniform usampler2D gObjectId;
layout(set = 1, binding = 8) uniform sampler2D litImage;  // the deferred lighting's image (the P-buffer)
// Per object, the technique's own data (heuristic_rt: the selected effects' bits).
layout(std430, set = 1, binding = 9) readonly buffer TechniqueObjectData { uint objectData[]; };
layout(set = 1, binding = 10) uniform sampler2D ssrColor;  // ssr_trace.comp's outputs
layout(set = 1, binding = 11) uniform sampler2D ssrHit;
// Per texel, kTexelRecords vec4 of terms for the technique's later passes (composite, debug images).
layout(std430, set = 1, binding = 12) buffer Texels { vec4 texels[]; };
// The technique's own counters (work that is not a ray).
layout(std430, set = 1, binding = 13) buffer TechniqueCounts { uint techniqueCounts[]; };
// The texels a compacted launch traces (frame.rules.z = 1): the indirect launch's size, then the
// texels packed by packTexel(), in no particular order (each invocation writes its own texel only).
layout(std430, set = 1, binding = 14) buffer TexelList {
    TexelListHeader listHeader;
    uint listedTexels[];
};

const int kTexelRecords = 4;

// The object seen at a texel, or -1 for the sky.
int gbufferObject(ivec2 texel) { return int(texelFetch(gObjectId, texel, 0).r) - 1; }

// The row-major index of a texel in radianceOut and (times kTexelRecords) texels.
int texelIndex(ivec2 texel) { return texel.y * frame.size.x + texel.x; }

uint packTexel(ivec2 texel) { return uint(texel.x) | (uint(texel.y) << 16); }
ivec2 unpackTexel(uint packed) { return ivec2(packed & 0xFFFFu, packed >> 16); }

#endif
