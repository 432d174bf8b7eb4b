// What the SSR shaders (ssr_depth_pyramid.comp, ssr_trace.comp, ssr_composite.comp) and the C++ exchange, declared once
// for C++ and GLSL (as common/device_rays/shaders/device_ray_records.h): the C++ sees glm types in
// namespace hybridlab::ssr_records and static_asserts their layout. The uniform blocks hold only
// mat4 and vec4 members and the march list's header four uints, so std140, std430 and C++ agree
// without padding rules.
#ifndef SSR_RECORDS_H
#define SSR_RECORDS_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace hybridlab::ssr_records {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
using uint = std::uint32_t;
#define SSR_CONSTANT inline constexpr
#else
#define SSR_CONSTANT const
#endif

// The uniforms of ssr_depth_pyramid.comp.
struct PyramidUniforms {
    mat4 view;
    vec4 flags;  // x 1: refractive texels are marched too (SsrSettings::refractive)
};

// The uniforms of ssr_trace.comp.
struct SsrUniforms {
    mat4 view;
    mat4 projection;      // Vulkan clip, y down, reverse-Z
    vec4 cameraPosition;  // xyz; w 1 perspective, 0 orthographic
    vec4 cameraForward;   // xyz
    vec4 march;           // x max steps, y stride (pixels), z thickness (view depth), w max distance (world)
    vec4 screen;          // x width, y height, z edge fade (fraction of the smaller side), w near plane distance
    vec4 hiz;             // x the pyramid's top level
};

// The uniforms of ssr_composite.comp (the seam blur and composite after the device's ray tracing).
struct CompositeUniforms {
    ivec4 size;     // x width, y height, z blur radius (0: off)
    vec4 settings;  // x bilateral range sigma (0: plain Gaussian), y Walewski blend (1 or 0)
};

// The head of the march list (a storage buffer; the texels, packed x | y << 16, follow it): the
// indirect dispatch's group counts, then the number of texels listed.
struct MarchListHeader {
    uint groups[3];
    uint count;
};

// Invocations per work group: ssr_depth_pyramid.comp's is kSsrPyramidGroupSize squared (one per
// cell), ssr_trace.comp's kSsrMarchGroupSize (one per listed texel).
SSR_CONSTANT uint kSsrPyramidGroupSize = 8u;
SSR_CONSTANT uint kSsrMarchGroupSize = 64u;

#ifdef __cplusplus
static_assert(sizeof(PyramidUniforms) == 80 && sizeof(SsrUniforms) == 208 && sizeof(MarchListHeader) == 16);
static_assert(sizeof(CompositeUniforms) == 32);
}  // namespace hybridlab::ssr_records
namespace hybridlab {
#endif

// Bits of SsrPixel::flags (C++) and of ssrHit.z (ssr_trace.comp).
SSR_CONSTANT uint kSsrTraced = 1u << 0;       // a texel of the march list: a ray was marched
SSR_CONSTANT uint kSsrOffScreen = 1u << 1;    // the ray left the screen, or the view frustum through the near plane
SSR_CONSTANT uint kSsrBehind = 1u << 2;       // it passed behind a surface by more than the thickness and found no hit
SSR_CONSTANT uint kSsrOutOfSteps = 1u << 3;   // it ran out of steps
SSR_CONSTANT uint kSsrBackFace = 1u << 4;     // it hit the back of the surface seen at the hit pixel
SSR_CONSTANT uint kSsrMaxDistance = 1u << 5;  // it reached the maximum distance without a hit
SSR_CONSTANT uint kSsrFailures = kSsrOffScreen | kSsrBehind | kSsrOutOfSteps | kSsrBackFace | kSsrMaxDistance;

#ifdef __cplusplus
}  // namespace hybridlab
#endif
#undef SSR_CONSTANT

#endif
