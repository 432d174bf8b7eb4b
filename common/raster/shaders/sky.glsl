// skyRadiance() of common/raytrace/shading.cpp for a cube-map sky, in GLSL: the six faces as layers
// of an RGBA32F array image, read with texelFetch and filtered by hand as the C++ does. Shared by
// the lighting pass and the ray-tracing shaders.
#ifndef SKY_GLSL
#define SKY_GLSL

#include "cube_map.glsl"

// As Image::sampleBilinearWrap on sky face `face`.
vec3 sampleFaceBilinearWrap(sampler2DArray faces, int face, float u, float v) {
    ivec2 size = textureSize(faces, 0).xy;
    float x = u * float(size.x) - 0.5;
    float y = v * float(size.y) - 0.5;
    float fx = floor(x), fy = floor(y);
    float tx = x - fx, ty = y - fy;
    int x0 = int(fx) % size.x, y0 = int(fy) % size.y;
    if (x0 < 0) x0 += size.x;
    if (y0 < 0) y0 += size.y;
    int x1 = x0 + 1 == size.x ? 0 : x0 + 1, y1 = y0 + 1 == size.y ? 0 : y0 + 1;
    vec3 top = texelFetch(faces, ivec3(x0, y0, face), 0).rgb * (1.0 - tx) + texelFetch(faces, ivec3(x1, y0, face), 0).rgb * tx;
    vec3 bottom = texelFetch(faces, ivec3(x0, y1, face), 0).rgb * (1.0 - tx) + texelFetch(faces, ivec3(x1, y1, face), 0).rgb * tx;
    return top * (1.0 - ty) + bottom * ty;
}

// The cube map's radiance in world direction d.
vec3 skyCubeRadiance(sampler2DArray faces, vec3 d) {
    int face;
    vec2 uv;
    cubeMapCoordinate(d, face, uv);
    vec2 size = vec2(textureSize(faces, 0).xy);
    // Clamp to the face instead of wrapping across its edge.
    float x = clamp(uv.x * size.x, 0.5, size.x - 0.5) / size.x;
    float y = clamp(uv.y * size.y, 0.5, size.y - 0.5) / size.y;
    return sampleFaceBilinearWrap(faces, face, x, y);
}

#endif
