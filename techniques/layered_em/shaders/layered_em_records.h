// What the layered-EM lens pass (layered_em.vert, layered_em.frag) and LayeredEmPass exchange,
// declared once for C++ and GLSL (as common/device_rays/shaders/device_ray_records.h): the C++ sees glm
// types in namespace hybridlab::layered_em_records and static_asserts their layout. Only vec4-sized
// members, so std430 (the vertex buffer, the push constants) and C++ agree without padding rules.
#ifndef LAYERED_EM_RECORDS_H
#define LAYERED_EM_RECORDS_H

#ifdef __cplusplus
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace hybridlab::layered_em_records {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
#define LAYERED_EM_CONSTANT inline constexpr
#else
#define LAYERED_EM_CONSTANT const
#endif

// The layers a draw composites at most, and its path terms (the lens paths' kPathTerms).
LAYERED_EM_CONSTANT int kMaxDrawnLayers = 4;
LAYERED_EM_CONSTANT int kDrawnPathTerms = 2;

// One vertex of the tessellated lens, read by gl_VertexIndex from a storage buffer.
struct LensVertex {
    vec4 position;                                       // world
    vec4 weight[kDrawnPathTerms];                        // F G per term
    vec4 sky[kDrawnPathTerms];                           // F G * sky(exit direction) per term
    vec4 direction[kDrawnPathTerms * kMaxDrawnLayers];   // [term * kMaxDrawnLayers + layer]: xyz shell point minus EM origin (unnormalised), w level of detail
};

// The push constants of one lens system's draw.
struct LensDrawConstants {
    mat4 viewProj;
    vec4 cameraPosition;  // xyz; w: relative depth tolerance of the G-buffer occlusion test
    ivec4 maps;           // layers, level-0 texels a face side, first texel of viewpoint sample A's maps, of B's
    vec4 blend;           // weights of viewpoint samples A and B
    ivec4 chain;          // MIP levels of a map, texels of a map's whole chain (cubeMapLevels, cubeMapTexelCount)
};

#ifdef __cplusplus
static_assert(sizeof(LensVertex) == 16 * (1 + 2 * kDrawnPathTerms + kDrawnPathTerms * kMaxDrawnLayers));
static_assert(sizeof(LensVertex) == 208 && sizeof(LensDrawConstants) == 128);
}  // namespace hybridlab::layered_em_records
#endif
#undef LAYERED_EM_CONSTANT

#endif
