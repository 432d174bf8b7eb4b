#version 460
// Layered-EM lens pass, vertex stage (Hakura & Snyder 2001 §5): the tessellated lens with its
// per-vertex attributes, read from a storage buffer by gl_VertexIndex. Every attribute is
// interpolated perspective-correctly (smooth), as rasterizeLens's barycentrics
// (techniques/layered_em/README.md, "Contract with the renderer", 1-2).
#extension GL_GOOGLE_include_directive : require
#include "layered_em_bindings.glsl"

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 pathWeight[kDrawnPathTerms];     // F G of each term
layout(location = 3) out vec3 skyWeight[kDrawnPathTerms];      // F G times the sky in the term's exit direction
layout(location = 5) out vec4 direction[kDrawnPathTerms * kMaxDrawnLayers];  // [term * kMaxDrawnLayers + layer]: the cube-map index, w its level of detail

void main() {
    LensVertex v = vertices[gl_VertexIndex];
    worldPosition = v.position.xyz;
    for (int t = 0; t < kDrawnPathTerms; ++t) {
        pathWeight[t] = v.weight[t].xyz;
        skyWeight[t] = v.sky[t].xyz;
        for (int l = 0; l < kMaxDrawnLayers; ++l) direction[t * kMaxDrawnLayers + l] = v.direction[t * kMaxDrawnLayers + l];
    }
    gl_Position = pc.viewProj * vec4(v.position.xyz, 1.0);
}
