#version 460
// Layered-EM lens pass, fragment stage (Hakura & Snyder 2001 §4-§5): per term and layer the cube
// map's MIP chain read at the interpolated index and level of detail with cubeMapLookup's texels
// and weights (texel reads, no hardware filtering), layers composited front to back with "over" on premultiplied RGBA, the sky
// behind the last layer, times the interpolated F G, the two terms summed; the two nearest
// viewpoint samples blended. compositeLensPixel (techniques/layered_em/lens_draw.cpp) computes the
// same on the CPU; LayeredEmPass.GpuCompositesLayersSkyAndViewpointsAsTheCpu holds them equal.
// Fragments behind what the G-buffer shows at the pixel are discarded (the lens is occluded).
#extension GL_GOOGLE_include_directive : require
#include "cube_map.glsl"
#include "layered_em_bindings.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 pathWeight[kDrawnPathTerms];
layout(location = 3) in vec3 skyWeight[kDrawnPathTerms];
layout(location = 5) in vec4 direction[kDrawnPathTerms * kMaxDrawnLayers];

layout(location = 0) out vec4 outColor;  // radiance; alpha 1 (coverage)

// The depth test before shading (discard does not disable it): a fragment discarded here is behind
// what the G-buffer shows, and so is every lens fragment its depth then hides.
layout(early_fragment_tests) in;

// The MIP chain (em_cube_map.cpp): level k has max(1, size >> k) texels a side; its length and
// texel count come with the push constants.
int levelSize(int level) { return max(1, pc.maps.y >> level); }
int levelOffset(int level) {
    int offset = 0;
    for (int k = 0; k < level; ++k) offset += 6 * levelSize(k) * levelSize(k);
    return offset;
}

// cubeMapLookup: in levels floor(lod) and the next, the four texels (from a map's first texel) and
// bilinear weights around texel centres (i + 0.5) / side, clamped to the face, each level's weights
// times its share of lod.
struct Taps {
    ivec4 texel[2];  // per level
    vec4 weight[2];
};
void levelTaps(int face, vec2 st, int level, float scale, out ivec4 texel, out vec4 weight) {
    int side = levelSize(level);
    float fs = float(side);
    float u = clamp(st.x * fs - 0.5, 0.0, fs - 1.0), v = clamp(st.y * fs - 0.5, 0.0, fs - 1.0);
    int i0 = min(int(u), side - 1), j0 = min(int(v), side - 1);
    int i1 = min(i0 + 1, side - 1), j1 = min(j0 + 1, side - 1);
    float fu = u - float(i0), fv = v - float(j0);
    int b = levelOffset(level) + face * side * side;
    texel = ivec4(b + j0 * side + i0, b + j0 * side + i1, b + j1 * side + i0, b + j1 * side + i1);
    weight = scale * vec4((1.0 - fu) * (1.0 - fv), fu * (1.0 - fv), (1.0 - fu) * fv, fu * fv);
}
Taps cubeLookup(vec4 index) {
    int face;
    vec2 st;
    cubeMapCoordinate(index.xyz, face, st);
    int last = pc.chain.x - 1;
    float lod = clamp(index.w, 0.0, float(last));
    int level = min(int(lod), last);
    float f = lod - float(level);
    Taps t;
    levelTaps(face, st, level, 1.0 - f, t.texel[0], t.weight[0]);
    levelTaps(face, st, min(level + 1, last), f, t.texel[1], t.weight[1]);
    return t;
}

vec4 fetch(int base, Taps t) {
    vec4 c = vec4(0.0);
    for (int k = 0; k < 2; ++k) {
        if (t.weight[k] == vec4(0.0)) continue;  // a level lod's fraction leaves out (most lookups read one)
        c += t.weight[k].x * texels[base + t.texel[k].x] + t.weight[k].y * texels[base + t.texel[k].y] +
             t.weight[k].z * texels[base + t.texel[k].z] + t.weight[k].w * texels[base + t.texel[k].w];
    }
    return c;
}

void main() {
    vec4 g = texelFetch(gbufferPosition, ivec2(gl_FragCoord.xy), 0);
    if (g.w > 0.0) {
        float seen = distance(g.xyz, pc.cameraPosition.xyz), here = distance(worldPosition, pc.cameraPosition.xyz);
        if (seen < here * (1.0 - pc.cameraPosition.w)) discard;
    }
    // Per term, both viewpoint samples' layers over one another; the two samples share the shells,
    // so each layer's lookup (texels and weights) serves both.
    int layerTexels = pc.chain.y;
    bool blend = pc.blend.y > 0.0;
    vec3 c = vec3(0.0);
    for (int t = 0; t < kDrawnPathTerms; ++t) {
        vec4 a = vec4(0.0), b = vec4(0.0);
        for (int l = 0; l < pc.maps.x; ++l) {
            if (a.a >= 1.0 && (!blend || b.a >= 1.0)) break;  // opaque: the layers behind add (1 - a.a) * ... = 0
            Taps taps = cubeLookup(direction[t * kMaxDrawnLayers + l]);
            a += (1.0 - a.a) * fetch(pc.maps.z + l * layerTexels, taps);
            if (blend) b += (1.0 - b.a) * fetch(pc.maps.w + l * layerTexels, taps);
        }
        c += pc.blend.x * (pathWeight[t] * a.rgb + (1.0 - a.a) * skyWeight[t]);
        if (blend) c += pc.blend.y * (pathWeight[t] * b.rgb + (1.0 - b.a) * skyWeight[t]);
    }
    outColor = vec4(c, 1.0);
}
