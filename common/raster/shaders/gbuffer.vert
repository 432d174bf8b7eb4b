#version 460
// G-buffer pass, vertex stage (Walewski 2019 §3.1): world-space position, normal, uv and tangent.
// Also the vertex stage of the depth pre-pass and of the depth-equal visible-pixel pass, which
// must reproduce the depths exactly: the same code, and `precise` so that no pipeline contracts
// the arithmetic differently (`invariant gl_Position` would do too, but the validation layers
// warn about the decoration glslang puts on gl_PerVertex).
#extension GL_GOOGLE_include_directive : require
#include "scene_data.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inTangent;

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;   // not normalised: interpolated, then normalised (as RayScene)
layout(location = 2) out vec2 uv;
layout(location = 3) out vec4 worldTangent;  // xyz world tangent, w bitangent sign

void main() {
    ObjectData o = drawData.object;
    precise vec4 p = o.model * vec4(inPosition, 1.0);
    worldPosition = p.xyz;
    worldNormal = mat3(o.normalMatrix) * inNormal;
    uv = inUv;
    worldTangent = vec4(mat3(o.model) * inTangent.xyz, inTangent.w);
    precise vec4 clip = draw.viewProj * p;
    gl_Position = clip;
}
