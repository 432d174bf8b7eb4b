#version 460
// The template technique's shader: it only has to compile and be embedded.
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform Push { float level; } push;
layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D target;

void main() {
    imageStore(target, ivec2(gl_GlobalInvocationID.xy), vec4(vec3(push.level), 1.0));
}
