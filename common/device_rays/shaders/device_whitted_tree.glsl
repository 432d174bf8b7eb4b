// The Whitted ray tree on the device: the device's backend of the one walk
// (common/shading/whitted_tree.h, written once for both backends with the one shading model of
// common/shading), what every ray-generation shader that shades hits shares.
// device_whitted.rgen traces it from camera rays; device_gbuffer_rays.glsl starts it at G-buffer
// texels (the hybrids' secondary rays). Below: what the walk asks of a backend (trace a ray,
// resolve its hit, sample a texture over a ray cone, test a shadow ray, count a ray), each as the
// C++ backend (EmbreeTreeBackend, common/raytrace/embree_tree_backend.h) computes it on RayScene; the
// DeviceRays tests (tests/device_rays/test_device_rays.cpp) hold the images and ray counts of both
// backends equal. The walk iterates the tree with an explicit stack (whitted_tree.h says why), so
// the pipeline needs a recursion depth of 1 only.
#ifndef DEVICE_WHITTED_TREE_GLSL
#define DEVICE_WHITTED_TREE_GLSL

#include "device_rays.glsl"
#include "ray_geometry.h"
#include "shading.glsl"
#include "sky.glsl"
#include "device_medium_stack.glsl"
#include "whitted_tree_types.h"

layout(location = 0) rayPayloadEXT HitPayload hit;
layout(location = 1) rayPayloadEXT ShadowPayload shadow;

// A resolved hit: as SurfaceHit and RayScene::resolveHit.
struct Surface {
    vec3 position;
    vec3 geometricNormal;
    vec3 shadingNormal;
    vec2 uv;
    float uvDensityLod;
    uint material;
    uint object;
};

uint countShadow = 0u, countReflection = 0u, countRefraction = 0u, countMediumErrors = 0u;

// The sky along d (skyRadiance(), common/raytrace/shading.h).
vec3 skyRadiance(vec3 d) {
    if (frame.skyColor.a == 0.0) return frame.skyColor.rgb;
    return skyCubeRadiance(skyFaces, d);
}

Surface resolveHit() {
    DeviceInstance inst = instances[hit.instance];
    uint first = inst.topology.x + 3u * hit.primitive;
    uint base = inst.geometry.w;
    DeviceVertex v0 = vertices[base + indices[first]], v1 = vertices[base + indices[first + 1u]], v2 = vertices[base + indices[first + 2u]];
    float u = hit.barycentrics.x, v = hit.barycentrics.y, w = 1.0 - u - v;
    mat4 M = inst.toWorld;
    mat3 N = mat3(inst.normalToWorld);
    vec3 p0 = (M * vec4(v0.positionU.xyz, 1.0)).xyz, p1 = (M * vec4(v1.positionU.xyz, 1.0)).xyz, p2 = (M * vec4(v2.positionU.xyz, 1.0)).xyz;
    Surface s;
    s.material = inst.geometry.z;
    s.object = inst.geometry.x;
    s.position = w * p0 + u * p1 + v * p2;
    s.geometricNormal = triangleGeometricNormal(hit.instance, hit.primitive);
    s.shadingNormal = normalize(N * (w * v0.normalV.xyz + u * v1.normalV.xyz + v * v2.normalV.xyz));
    s.uv = vec2(0.0);
    s.uvDensityLod = -1.0 / 0.0;
    uint flags = inst.topology.y;
    if ((flags & kHasUvs) != 0u) {
        vec2 uv0 = vec2(v0.positionU.w, v0.normalV.w), uv1 = vec2(v1.positionU.w, v1.normalV.w), uv2 = vec2(v2.positionU.w, v2.normalV.w);
        s.uv = w * uv0 + u * uv1 + v * uv2;
        vec2 a = uv1 - uv0, b = uv2 - uv0;
        float uvArea = abs(a.x * b.y - a.y * b.x);
        float worldArea = length(cross(p1 - p0, p2 - p0));
        if (uvArea > 0.0 && worldArea > 0.0) s.uvDensityLod = 0.5 * log2(uvArea / worldArea);
    }
    DeviceMaterial m = materials[s.material];
    if (m.textures.y >= 0 && (flags & kHasTangents) != 0u && (flags & kHasUvs) != 0u) {
        vec4 t4 = w * v0.tangent + u * v1.tangent + v * v2.tangent;
        vec3 t = normalize(mat3(M) * t4.xyz);
        t = normalize(t - s.shadingNormal * dot(s.shadingNormal, t));
        vec3 b = cross(s.shadingNormal, t) * (t4.w < 0.0 ? -1.0 : 1.0);
        vec2 tc = s.uv * m.tilingOffset.xy + m.tilingOffset.zw;
        vec3 tn = textureLod(sceneTextures[nonuniformEXT(m.textures.y)], tc, 0.0).rgb * 2.0 - 1.0;
        s.shadingNormal = normalize(t * tn.x + b * tn.y + s.shadingNormal * tn.z);
    }
    return s;
}

// As diffuseTextureValue(): the diffuse texture over a footprint of 2^uvLod uv units.
vec3 diffuseTextureValue(DeviceMaterial m, vec2 uv, float uvLod) {
    if (m.textures.x < 0) return vec3(1.0);
    vec2 t = uv * m.tilingOffset.xy + m.tilingOffset.zw;
    vec2 size = vec2(textureSize(sceneTextures[nonuniformEXT(m.textures.x)], 0));
    float lod = uvLod + textureUvUnitLod(size.x, size.y, m.tilingOffset.xy);
    return textureLod(sceneTextures[nonuniformEXT(m.textures.x)], t, lod).rgb;
}

// As RayScene::transmittance(): from a point in media of total absorption `startAbsorption`
// to a light at distance `tmax` (infinite: a directional light).
vec3 transmittance(vec3 origin, vec3 direction, float tmax, vec3 startAbsorption) {
    const bool finite = tmax < 3.0e38;
    shadow.transmittance = vec3(1.0);
    shadow.missed = 0u;
    shadow.opticalDepth = vec3(0.0);
    shadow.lightDistance = finite ? tmax : -1.0;
    shadow.crossings = 0;
    traceRayEXT(topLevel, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT, 0xFF, kShadowRay, 0, kShadowRay,
                origin, 0.0, direction, min(tmax, 3.0e38), 1);
    if (shadow.missed == 0u) return vec3(0.0);
    return shadowRayTransmittance(shadow.transmittance, shadow.opticalDepth, startAbsorption, shadow.lightDistance);
}

int lightCount() { return frame.size.z; }
LightSample lightSample(int i, vec3 p) { return sampleLightRecord(lights[i], p); }
bool lightCastsShadows(int i) { return lights[i].shadow.x >= 0; }

// As RayScene::intersect(): the closest hit's distance (< 0: a miss), the hit in the payload.
float traceRay(vec3 origin, vec3 direction) {
    traceRayEXT(topLevel, gl_RayFlagsOpaqueEXT, 0xFF, kRadianceRay, 0, kRadianceRay, origin, 0.0, direction, 3.0e38, 0);
    return hit.t;
}

SurfaceMaterial surfaceMaterial(DeviceMaterial m) {
    SurfaceMaterial s;
    s.emission = m.emission.rgb;
    s.ambient = m.ambient.rgb;
    s.diffuse = m.diffuse.rgb;
    s.specular = m.specular.rgb;
    s.specularExponent = m.specular.a;
    s.reflectivity = m.optical.x;
    s.ior = m.optical.y;
    s.opacity = m.optical.z;
    s.fresnel = m.optical.w != 0.0;
    return s;
}
SurfaceMaterial surfaceMaterial(Surface s) { return surfaceMaterial(materials[s.material]); }

// The diffuse texture over the ray cone's footprint (none on a G-buffer surface: its colours are
// textured already).
vec3 diffuseTexture(Surface s, float coneWidth, vec3 incoming) {
    if (s.material == kNoAbsorption) return vec3(1.0);
    return diffuseTextureValue(materials[s.material], s.uv, uvFootprintLod(s.uvDensityLod, coneWidth, incoming, s.geometricNormal));
}

vec3 shadowTransmittance(vec3 origin, vec3 direction, float distance, vec3 startAbsorption) {
    return transmittance(origin, direction, distance, startAbsorption);
}

// As RayCone::at; none without ray cones (texture_filter = "none").
float coneWidthAt(float width, float t) { return frame.settings.w != 0.0 ? width + frame.cone.y * t : 0.0; }

TreeSettings treeSettings() {
    TreeSettings t;
    t.maxDepth = frame.size.w;
    t.depthLimitLocal = frame.rules.x == 0u;
    t.importanceCutoff = frame.settings.x;
    t.walewski = frame.settings.y != 0.0;
    t.shadows = frame.settings.z != 0.0;
    t.sceneAmbient = frame.ambient.rgb;
    t.ambientIor = frame.ambient.a;
    return t;
}

MediumEntry mediumEntry(Surface s) { return s.object | (s.material << 16); }

void countRay(int kind) {
    if (kind == kRayShadow) ++countShadow;
    else if (kind == kRayReflection) ++countReflection;
    else if (kind == kRayRefraction) ++countRefraction;
    else ++countMediumErrors;
}

#include "whitted_tree.h"

// The radiance along a camera ray (depth 0) and the rays it spawns: the effects frame.effects
// selects at its first hit.
vec3 traceCameraTree(PendingRay root) { return traceTree(root, bvec3(frame.effects.xyz != uvec3(0u))); }

// The per-pixel counts of the invocation, added to the launch's counters (rayCounts).
void addRayCounts() {
    if (countShadow > 0u) atomicAdd(rayCounts[1], countShadow);
    if (countReflection > 0u) atomicAdd(rayCounts[2], countReflection);
    if (countRefraction > 0u) atomicAdd(rayCounts[3], countRefraction);
    if (countMediumErrors > 0u) atomicAdd(rayCounts[4], countMediumErrors);
}

#endif
