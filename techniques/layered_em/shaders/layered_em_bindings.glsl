// The bindings layered_em.vert and layered_em.frag share: the per-vertex records, the inferred
// cube maps, the G-buffer positions and the push constants of one lens system's draw (their
// records in layered_em_records.h).
#include "layered_em_records.h"

layout(std430, set = 0, binding = 0) readonly buffer Vertices { LensVertex vertices[]; };
// Premultiplied RGBA texels of the cube maps this frame reads, each map's MIP chain level after
// level from its base (cubeMapLevelOffset), a level face * side * side + row * side + column.
layout(std430, set = 0, binding = 1) readonly buffer Texels { vec4 texels[]; };
layout(set = 0, binding = 2) uniform sampler2D gbufferPosition;

layout(push_constant) uniform DrawConstants { LensDrawConstants pc; };
