#version 460
// Layered-EM lens pass, fragment stage (Hakura & Snyder 2001 §4-§5): per term and layer the cube
// map read at the interpolated index with cubeMapLookup's texels and weights (texel reads, no
// hardware filtering), layers composited front to back with "over" on premultiplied RGBA, the sky
// behind the last layer, times the interpolated F G, the two terms summed; the two nearest
// viewpoint samples blended. The twin of compositeLensPixel (techniques/layered_em/lens_draw.cpp).
// Fragments behind what the G-buffer shows at the pixel are discarded (the lens is occluded).
#extension GL_GOOGLE_include_directive : require
#include "layered_em_common.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 pathWeight[2];
layout(location = 3) in vec3 skyWeight[2];
layout(location = 5) in vec3 direction[2 * kMaxLayers];

layout(location = 0) out vec4 outColor;  // radiance; alpha 1 (coverage)

// cubeMapCoordinate (em_cube_map.cpp): the face by the major axis, OpenGL's s/t table.
void cubeCoordinate(vec3 d, out int face, out vec2 st) {
    vec3 a = abs(d);
    float sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x >= 0.0 ? 0 : 1;
        ma = a.x;
        sc = d.x >= 0.0 ? -d.z : d.z;
        tc = -d.y;
    } else if (a.y >= a.z) {
        face = d.y >= 0.0 ? 2 : 3;
        ma = a.y;
        sc = d.x;
        tc = d.y >= 0.0 ? d.z : -d.z;
    } else {
        face = d.z >= 0.0 ? 4 : 5;
        ma = a.z;
        sc = d.z >= 0.0 ? d.x : -d.x;
        tc = -d.y;
    }
    st = ma > 0.0 ? vec2(0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0)) : vec2(0.5);
}

// cubeMapLookup: bilinear over texel centres (i + 0.5) / size, clamped to the face.
vec4 cubeLookup(int base, vec3 d) {
    int size = pc.maps.y;
    int face;
    vec2 st;
    cubeCoordinate(d, face, st);
    float fs = float(size);
    float u = clamp(st.x * fs - 0.5, 0.0, fs - 1.0), v = clamp(st.y * fs - 0.5, 0.0, fs - 1.0);
    int i0 = min(int(u), size - 1), j0 = min(int(v), size - 1);
    int i1 = min(i0 + 1, size - 1), j1 = min(j0 + 1, size - 1);
    float fu = u - float(i0), fv = v - float(j0);
    int b = base + face * size * size;
    return (1.0 - fu) * (1.0 - fv) * texels[b + j0 * size + i0] + fu * (1.0 - fv) * texels[b + j0 * size + i1] +
           (1.0 - fu) * fv * texels[b + j1 * size + i0] + fu * fv * texels[b + j1 * size + i1];
}

// One viewpoint sample's image of the lens at this pixel.
vec3 viewpointRadiance(int base) {
    int layerTexels = 6 * pc.maps.y * pc.maps.y;
    vec3 sum = vec3(0.0);
    for (int t = 0; t < 2; ++t) {
        vec4 acc = vec4(0.0);
        for (int l = 0; l < pc.maps.x; ++l) acc += (1.0 - acc.a) * cubeLookup(base + l * layerTexels, direction[t * kMaxLayers + l]);
        sum += pathWeight[t] * acc.rgb + (1.0 - acc.a) * skyWeight[t];
    }
    return sum;
}

void main() {
    vec4 g = texelFetch(gbufferPosition, ivec2(gl_FragCoord.xy), 0);
    if (g.w > 0.0) {
        float seen = distance(g.xyz, pc.cameraPosition.xyz), here = distance(worldPosition, pc.cameraPosition.xyz);
        if (seen < here * (1.0 - pc.cameraPosition.w)) discard;
    }
    vec3 c = pc.blend.x * viewpointRadiance(pc.maps.z);
    if (pc.blend.y > 0.0) c += pc.blend.y * viewpointRadiance(pc.maps.w);
    outColor = vec4(c, 1.0);
}
