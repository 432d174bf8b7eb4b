#version 460
// ssr_fallback's reflection composer after the ray-traced stage, on the device: the seam blur
// (as blurReflectionSeams, techniques/ssr_fallback/seam_blur.cpp, which states the rule; the test
// SsrFallbackAgreesWithEmbreeOnTheFourScenes holds them equal)
// and the composition of each composer texel from the terms device_ssr_fallback.rgen left in
// texels[] (4 vec4 a texel: M and its source, C and o_m, R and o_r, flags).
#extension GL_GOOGLE_include_directive : require
#include "shading.glsl"
#include "ssr_records.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std140, set = 0, binding = 0) uniform Composite { CompositeUniforms u; };
layout(std430, set = 0, binding = 1) readonly buffer Texels { vec4 texels[]; };
layout(std430, set = 0, binding = 2) buffer Output { vec4 radianceOut[]; };
layout(std430, set = 0, binding = 3) buffer Counts { uint blurredTexels; };

const float kSourceNone = 0.0;

float sourceAt(ivec2 p) { return texels[4 * (p.y * u.size.x + p.x)].w; }
vec3 reflectionAt(ivec2 p) { return texels[4 * (p.y * u.size.x + p.x)].xyz; }

bool inside(ivec2 p) { return p.x >= 0 && p.y >= 0 && p.x < u.size.x && p.y < u.size.y; }

// A reflecting texel with a reflecting 4-neighbour from another path.
bool seam(ivec2 p) {
    float s = sourceAt(p);
    if (s == kSourceNone) return false;
    const ivec2 offsets[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    for (int k = 0; k < 4; ++k) {
        ivec2 q = p + offsets[k];
        if (!inside(q)) continue;
        float n = sourceAt(q);
        if (n != kSourceNone && n != s) return true;
    }
    return false;
}

// c / (1 + c) per channel: colour differences on a bounded scale, whatever the radiance.
vec3 compressed(vec3 c) { return c / (vec3(1.0) + max(c, vec3(0.0))); }

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (!inside(p)) return;
    const int i = p.y * u.size.x + p.x;
    if (texels[4 * i + 3].x == 0.0) return;  // not in the composer: the ray-traced stage wrote its colour
    const int radius = u.size.z;
    const float rangeSigma = u.settings.x;
    vec3 M = reflectionAt(p);
    // The band: within `radius` (Chebyshev distance) of a seam texel.
    bool band = false;
    for (int dy = -radius; dy <= radius && !band && radius > 0; ++dy) {
        for (int dx = -radius; dx <= radius && !band; ++dx)
            if (inside(p + ivec2(dx, dy)) && seam(p + ivec2(dx, dy))) band = true;
    }
    if (radius > 0 && band) {
        const float sigma = 0.5 * float(radius);
        const vec3 centre = compressed(M);
        vec3 sum = vec3(0.0);
        float weight = 0.0;
        for (int dy = -radius; dy <= radius; ++dy) {
            for (int dx = -radius; dx <= radius; ++dx) {
                ivec2 q = p + ivec2(dx, dy);
                if (!inside(q) || sourceAt(q) == kSourceNone) continue;
                float w = exp(-0.5 * float(dx * dx) / (sigma * sigma)) * exp(-0.5 * float(dy * dy) / (sigma * sigma));
                if (rangeSigma > 0.0) {
                    vec3 d = compressed(reflectionAt(q)) - centre;
                    w *= exp(-0.5 * dot(d, d) / (rangeSigma * rangeSigma));
                }
                sum += w * reflectionAt(q);
                weight += w;
            }
        }
        M = sum / weight;
        atomicAdd(blurredTexels, 1u);
    }
    const vec4 C = texels[4 * i + 1], R = texels[4 * i + 2];
    radianceOut[i] = vec4(compose(C.w, R.w, M, R.rgb, C.rgb, u.settings.y != 0.0), 1.0);
}
