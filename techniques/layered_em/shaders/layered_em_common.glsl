// Shared by layered_em.vert and layered_em.frag: the per-vertex record, the inferred cube maps and
// the push constants of one lens system's draw (twins of the structs in
// techniques/layered_em/layered_em_pass.cpp).
const int kMaxLayers = 4;

struct LensVertex {
    vec4 position;                     // world
    vec4 weight[2];                    // F G per term
    vec4 sky[2];                       // F G * sky(exit direction) per term
    vec4 direction[2 * kMaxLayers];    // per term and layer: xyz shell point minus EM origin (unnormalised), w level of detail
};

layout(std430, set = 0, binding = 0) readonly buffer Vertices { LensVertex vertices[]; };
// Premultiplied RGBA texels of the cube maps this frame reads, each map's MIP chain level after
// level from its base (cubeMapLevelOffset), a level face * side * side + row * side + column.
layout(std430, set = 0, binding = 1) readonly buffer Texels { vec4 texels[]; };
layout(set = 0, binding = 2) uniform sampler2D gbufferPosition;

layout(push_constant) uniform DrawConstants {
    mat4 viewProj;
    vec4 cameraPosition;  // xyz; w: relative depth tolerance of the G-buffer occlusion test
    ivec4 maps;           // layers, level-0 texels a face side, first texel of viewpoint sample A's maps, of B's
    vec4 blend;           // weights of viewpoint samples A and B
    ivec4 chain;          // MIP levels of a map, texels of a map's whole chain (cubeMapLevels, cubeMapTexelCount)
} pc;
