#version 460
// Depth-only geometry (shadow maps): position through the object's model matrix and the light's
// view-projection.
#extension GL_GOOGLE_include_directive : require
#include "scene_data.glsl"

layout(location = 0) in vec3 inPosition;

void main() {
    gl_Position = draw.viewProj * (drawData.object.model * vec4(inPosition, 1.0));
}
