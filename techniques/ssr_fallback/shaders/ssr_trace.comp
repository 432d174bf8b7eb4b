#version 460
// Screen-space reflections (de Macedo & Rodrigues §III, first step of the reflection composer): for
// every opaque reflective G-buffer texel, the mirror ray is marched through the depth of the
// G-buffer with the perspective-correct DDA of McGuire & Mara (JCGT 3(4), 2014, Listing 4): the
// homogeneous camera-space point Q = p / w and k = 1 / w are affine in screen space, so they are
// stepped with the pixel; a step hits where the ray's depth interval over the step meets the
// surface's depth slab [d, d + thickness]. Outputs the lit image at the hit with a confidence, and
// why the ray failed (the mask the ray-traced fallback reads, the paper's second step). With
// kHiZ, the ray instead walks the min-depth pyramid (ssr_depth_pyramid.comp) as FidelityFX SSSR
// does: up a level after a cell the ray crosses wholly in front of its nearest surface, down a
// level where it may meet it, the thickness test at level 0. One invocation per texel of the march
// list that ssr_depth_pyramid.comp wrote (dispatched indirectly); the outputs of the other texels
// keep their cleared values (colour 0, hit (-1, -1), no flags).
#extension GL_GOOGLE_include_directive : require
#include "ssr_records.h"

layout(local_size_x = kSsrMarchGroupSize) in;

layout(constant_id = 0) const bool kHiZ = false;

layout(std140, set = 0, binding = 0) uniform Uniforms { SsrUniforms u; };
layout(set = 0, binding = 1) uniform sampler2D gPosition;
layout(set = 0, binding = 2) uniform sampler2D gNormal;
layout(set = 0, binding = 5) uniform sampler2D litImage;
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D ssrColor;  // rgb the lit image at the hit, a confidence
layout(set = 0, binding = 7, rgba32f) uniform writeonly image2D ssrHit;    // xy hit pixel (-1 without), z flag bits, w steps
layout(set = 0, binding = 8) uniform sampler2D depthPyramid;               // min view depth per cell, by level (linear: level 0 only)
layout(std430, set = 0, binding = 9) readonly buffer MarchList {
    MarchListHeader header;
    uint texels[];  // x | y << 16
} marchList;

const float kSkyDepth = 1e30;

// The view depth (distance along the viewing direction, positive in front) seen at a texel: level 0
// of the depth pyramid (sky: kSkyDepth).
float sceneDepth(ivec2 pixel) { return texelFetch(depthPyramid, pixel, 0).r; }

// Camera space to pixel coordinates (origin at the top-left corner of the image).
vec2 toPixel(vec4 clip) { return (clip.xy / clip.w * 0.5 + 0.5) * u.screen.xy; }

// The DDA state of McGuire & Mara's Listing 4: P the screen point (permuted so that x is the major
// axis), Q.z the homogeneous camera-space depth, k = 1 / w.
struct March {
    vec2 P;
    float Qz;
    float k;
};

void main() {
    if (gl_GlobalInvocationID.x >= marchList.header.count) return;
    uint packed = marchList.texels[gl_GlobalInvocationID.x];
    ivec2 pixel = ivec2(packed & 0xffffu, packed >> 16);
    ivec2 size = ivec2(u.screen.xy);

    vec3 p = texelFetch(gPosition, pixel, 0).xyz;
    vec4 normalAndFacing = texelFetch(gNormal, pixel, 0);
    vec3 n = normalAndFacing.w < 0.0 ? -normalAndFacing.xyz : normalAndFacing.xyz;  // towards the viewer
    vec3 incoming = u.cameraPosition.w > 0.0 ? normalize(p - u.cameraPosition.xyz) : u.cameraForward.xyz;
    vec3 r = reflect(incoming, n);

    vec3 csOrig = (u.view * vec4(p, 1.0)).xyz;
    vec3 csDir = normalize(mat3(u.view) * r);
    // Clip the ray to the near plane (z = -near), McGuire & Mara's first lines.
    float maxDistance = u.march.w, nearZ = -u.screen.w;
    bool nearClipped = csOrig.z + csDir.z * maxDistance > nearZ;
    float rayLength = nearClipped ? (nearZ - csOrig.z) / csDir.z : maxDistance;
    vec3 csEnd = csOrig + csDir * rayLength;

    vec4 H0 = u.projection * vec4(csOrig, 1.0), H1 = u.projection * vec4(csEnd, 1.0);
    float k0 = 1.0 / H0.w, k1 = 1.0 / H1.w;
    vec3 Q0 = csOrig * k0, Q1 = csEnd * k1;
    vec2 P0 = toPixel(H0), P1 = toPixel(H1);

    // Clip the screen segment to the image: Q and k are affine in screen space, so they shorten with it.
    vec2 delta = P1 - P0;
    float tExit = 1.0;
    for (int axis = 0; axis < 2; ++axis) {
        if (delta[axis] > 0.0) tExit = min(tExit, (float(size[axis]) - 0.5 - P0[axis]) / delta[axis]);
        else if (delta[axis] < 0.0) tExit = min(tExit, (0.5 - P0[axis]) / delta[axis]);
    }
    bool screenClipped = tExit < 1.0;
    tExit = max(tExit, 0.0);
    P1 = P0 + delta * tExit;
    Q1 = mix(Q0, Q1, tExit);
    k1 = mix(k0, k1, tExit);
    if (dot(P1 - P0, P1 - P0) < 1e-4) P1 += vec2(0.01);  // at least one pixel
    delta = P1 - P0;

    bool hit = false, behind = false;
    int steps = 0;
    vec2 hitPixel = vec2(-1.0);
    float thickness = u.march.z;
    int maxSteps = int(u.march.x);
    if (kHiZ) {
        // t runs along the clipped segment; Q.z and k are affine in t, so the ray's depth at t is
        // exact, and monotonic: its extremes over a cell are at the cell's entry and exit.
        float len = max(abs(delta.x), abs(delta.y));
        float nudge = 1e-3 / len;  // into the next cell
        float t = 1.0 / len;       // one pixel out, so that the ray does not find its own surface
        int level = 0, topLevel = int(u.hiz.x);
        while (t <= 1.0 && steps < maxSteps) {
            vec2 p = P0 + delta * t;
            float cellSize = float(1 << level);
            vec2 cellMin = floor(p / cellSize) * cellSize, cellMax = cellMin + cellSize;
            float tExit = 1.0;
            for (int axis = 0; axis < 2; ++axis) {
                if (delta[axis] > 0.0) tExit = min(tExit, (cellMax[axis] - P0[axis]) / delta[axis]);
                else if (delta[axis] < 0.0) tExit = min(tExit, (cellMin[axis] - P0[axis]) / delta[axis]);
            }
            float dEntry = -mix(Q0.z, Q1.z, t) / mix(k0, k1, t), dExit = -mix(Q0.z, Q1.z, tExit) / mix(k0, k1, tExit);
            float dMin = min(dEntry, dExit), dMax = max(dEntry, dExit);
            float nearest = texelFetch(depthPyramid, ivec2(cellMin / cellSize), level).r;
            ++steps;
            if (dMax < nearest) {  // wholly in front of the cell's nearest surface: skip the cell, coarser
                t = tExit + nudge;
                level = min(level + 1, topLevel);
                continue;
            }
            if (level > 0) {
                --level;
                continue;
            }
            if (dMin <= nearest + thickness) {
                hit = true;
                hitPixel = p;
                break;
            }
            if (nearest < kSkyDepth) behind = true;
            t = tExit + nudge;
            level = min(level + 1, topLevel);
        }
    } else {
        bool permute = abs(delta.x) < abs(delta.y);
        if (permute) {
            delta = delta.yx;
            P0 = P0.yx;
            P1 = P1.yx;
        }
        float stepDir = sign(delta.x);
        float invdx = stepDir / delta.x;
        float stride = u.march.y;
        vec2 dP = vec2(stepDir, delta.y * invdx);
        float dQz = (Q1.z - Q0.z) * invdx, dk = (k1 - k0) * invdx;
        float end = P1.x * stepDir;

        // Start one pixel out, so that the ray does not find its own surface.
        March m = March(P0 + dP, Q0.z + dQz, k0 + dk);
        // Coarse march with the stride; after a coarse hit (stride > 1), back up one stride and refine
        // with unit steps over it (the coarse hit stands when the refinement skips over the slab).
        float s = stride;
        int refineSteps = -1;  // unit steps left in the refinement; -1 while coarse
        while (m.P.x * stepDir <= end && steps < maxSteps && refineSteps != 0) {
            // The ray's depth across the pixel: from half a pixel back to half a pixel ahead (with a
            // stride, the pixels in between are skipped, not smeared into the test).
            float dMin = -(m.Qz - dQz * 0.5) / (m.k - dk * 0.5);
            float dMax = -(m.Qz + dQz * 0.5) / (m.k + dk * 0.5);
            if (dMin > dMax) {
                float t = dMin;
                dMin = dMax;
                dMax = t;
            }
            vec2 texel = permute ? m.P.yx : m.P;
            float sceneD = sceneDepth(ivec2(texel));
            ++steps;
            if (refineSteps > 0) --refineSteps;
            if (dMax >= sceneD && dMin <= sceneD + thickness) {
                hitPixel = texel;
                if (refineSteps < 0 && stride > 1.0) {
                    m.P -= dP * (stride - 1.0);
                    m.Qz -= dQz * (stride - 1.0);
                    m.k -= dk * (stride - 1.0);
                    s = 1.0;
                    refineSteps = int(stride);
                    continue;
                }
                hit = true;
                break;
            }
            if (dMin > sceneD + thickness && sceneD < kSkyDepth) behind = true;
            m.P += dP * s;
            m.Qz += dQz * s;
            m.k += dk * s;
        }
        if (refineSteps >= 0) hit = true;  // a coarse hit whose refinement did not land: keep the coarse pixel
    }

    uint flags = kSsrTraced;
    if (hit) {
        ivec2 h = ivec2(hitPixel);
        vec4 hn = texelFetch(gNormal, h, 0);
        vec3 hitNormal = hn.w < 0.0 ? -hn.xyz : hn.xyz;  // towards the viewer at the hit pixel
        if (dot(hitNormal, r) >= 0.0) flags |= kSsrBackFace;
    } else {
        if (steps >= maxSteps) flags |= kSsrOutOfSteps;
        else if (screenClipped || nearClipped) flags |= kSsrOffScreen;
        else flags |= kSsrMaxDistance;
        if (behind) flags |= kSsrBehind;
    }
    if (flags == kSsrTraced) {
        ivec2 h = ivec2(hitPixel);
        // Screen-edge fade: hits near the border are trusted less (their neighbourhood is cut off).
        float border = min(min(hitPixel.x, u.screen.x - hitPixel.x), min(hitPixel.y, u.screen.y - hitPixel.y));
        float fade = u.screen.z > 0.0 ? clamp(border / (u.screen.z * min(u.screen.x, u.screen.y)), 0.0, 1.0) : 1.0;
        imageStore(ssrColor, pixel, vec4(texelFetch(litImage, h, 0).rgb, fade));
    }
    imageStore(ssrHit, pixel, vec4(hitPixel, float(flags), float(steps)));
}
