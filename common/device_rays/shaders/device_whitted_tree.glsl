// The Whitted ray tree on the device, as WhittedTracer (common/raytrace/whitted_tracer.cpp)
// with the one shading model (common/shading, written once for both backends: the local colour's
// terms, the composition, which rays a hit traces, absorption): what every ray-generation shader
// that shades hits shares. device_whitted.rgen traces it from camera rays; device_gbuffer_rays.glsl starts it at
// G-buffer texels (the hybrids' secondary rays). Each function below computes what the C++
// function it names computes; the DeviceRays tests (tests/device_rays/test_device_rays.cpp) hold the images
// and ray counts of both backends equal.
//
// The ray tree is iterated with an explicit stack rather than recursed through closest-hit
// shaders. Recursion would need maxRayRecursionDepth >= max_depth + 2 (shadow rays from the
// deepest hit), and devices promise as little as 1; each level would also hold its payload live.
// The iteration needs a recursion depth of 1 only. Composition (composition.h compose()) is linear
// in the reflected, refracted and local terms, so each stack entry carries its throughput (its
// weight in the pixel's radiance) and adds its local term when popped; the importance cut-off
// (Walewski 2019 §3.3) looks at the product of weights along the path, which no traversal order
// changes, so the stack traces exactly the rays the recursion traces.
#ifndef DEVICE_WHITTED_TREE_GLSL
#define DEVICE_WHITTED_TREE_GLSL

#include "device_rays.glsl"
#include "ray_geometry.h"
#include "shading.glsl"
#include "sky.glsl"
#include "device_medium_stack.glsl"

layout(location = 0) rayPayloadEXT HitPayload hit;
layout(location = 1) rayPayloadEXT ShadowPayload shadow;

// A ray waiting to be traced.
struct PendingRay {
    vec3 origin;
    float importance;  // its weight in the pixel, for the cut-off
    vec3 direction;
    int depth;         // of its hit: 0 for camera rays
    vec3 throughput;   // its radiance's weight in the pixel
    float coneWidth;   // ray cone at its origin (ray_cone.h)
    MediumStack media; // the media it travels in
};
// A pop pushes at most two rays one level deeper: max_depth (at most 64) + 2 entries.
const int kMaxStack = 66;
PendingRay stack[kMaxStack];

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

// As WhittedTracer::localColor().
vec3 localColor(Surface s, DeviceMaterial m, vec3 n, vec3 ng, vec3 toViewer, bool shadowRays, float uvLod, vec3 mediumAbsorption) {
    vec3 tex = diffuseTextureValue(m, s.uv, uvLod);
    vec3 c = unlitTerm(m.emission.rgb, m.ambient.rgb, frame.ambient.rgb, tex);
    vec3 shadowOrigin = offsetRayOrigin(s.position, ng);
    for (int i = 0; i < frame.size.z; ++i) {
        LightData light = lights[i];
        LightSample ls = sampleLightRecord(light, s.position);
        vec3 direct = blinnPhong(n, m.diffuse.rgb * tex, m.specular.rgb, m.specular.a, toViewer, ls);
        if (direct == vec3(0.0)) continue;  // facing away, or outside a spot cone: no ray needed
        if (light.shadow.x >= 0 && frame.settings.z != 0.0 && shadowRays) {
            ++countShadow;
            direct *= transmittance(shadowOrigin, ls.toLight, ls.distance, mediumAbsorption);
        }
        c += direct;
    }
    return c;
}


// What a hit's reflected (M) or refracted (R) term is: traced (a ray to follow), or a value in
// its place (the sky where the effect is not traced at this hit, C under the importance cut-off,
// 0 past the depth limit).
struct HitTerm {
    bool traced;
    vec3 value;
    PendingRay ray;  // when traced: its origin, direction, importance, depth, cone and media (throughput 1)
};

// One hit shaded up to its secondary rays: as WhittedTracer::shadeParts() before it
// traces them.
struct HitShading {
    vec3 local;          // C
    float reflectivity;  // o_m (the Fresnel reflectance for dielectrics)
    float transparency;  // o_r
    bool composes;       // false: C alone
    bool tir;            // total internal reflection: R is M
    HitTerm reflected, refracted;
    vec3 skyReflected, skyRefracted;  // the rasterizer's environment terms (EnvironmentTerms)
};

// `effects` (shadows, reflection, refraction) are traced at this hit (TracedEffects); with
// `localGiven`, `givenLocal` stands in for C (the rasterizer's, shadowed by its maps). With
// `localIfWeighted`, C is shaded only where the composition weights it (WhittedTracer::shade()):
// not for clear glass, a perfect mirror or under total internal reflection with their rays traced,
// where h.local is 0.
HitShading shadeHit(Surface s, DeviceMaterial m, vec3 incoming, int depth, float importance, float coneWidth, MediumStack media,
                    bvec3 effects, bool localGiven, vec3 givenLocal, bool localIfWeighted) {
    HitShading h;
    // Work on the side the ray arrives from.
    ArrivalSide side = arrivalSide(incoming, s.geometricNormal, s.shadingNormal, m.optical.y, frame.ambient.a);
    vec3 ng = side.geometricNormal, n = side.shadingNormal;
    // The composition's weights, the depth limit, the importance cut-off and whether C weighs
    // (composition.h).
    HitScattering scattering = scatterAtHit(incoming, n, side.n1, side.n2, m.optical.x, m.optical.w != 0.0, m.optical.z, depth, frame.size.w,
                                            frame.rules.x == 0u, importance, frame.settings.x, effects.y, effects.z);
    h.reflectivity = scattering.reflectivity;
    h.transparency = scattering.transparency;
    h.composes = scattering.composes;
    h.tir = scattering.tir;
    bool tracesRays = scattering.tracesRays;
    float weightM = scattering.weightM, weightR = scattering.weightR;
    bool traceM = scattering.traceM, traceR = scattering.traceR;
    bool localWeighs = scattering.localWeighs;
    if (localGiven) {
        h.local = givenLocal;
    } else if (!localIfWeighted || localWeighs) {
        h.local = localColor(s, m, n, ng, -incoming, effects.x, uvFootprintLod(s.uvDensityLod, coneWidth, incoming, s.geometricNormal),
                             media.absorption);
    } else {
        h.local = vec3(0.0);
    }
    h.reflected.traced = false;
    h.refracted.traced = false;
    h.reflected.value = vec3(0.0);
    h.refracted.value = vec3(0.0);
    h.skyReflected = h.skyRefracted = h.local;
    if (!tracesRays) return h;
    vec3 reflected = scattering.reflectedDirection, refracted = scattering.refractedDirection;
    if (weightM > 0.0) h.skyReflected = skyRadiance(reflected);
    if (weightR > 0.0) h.skyRefracted = skyRadiance(refracted);
    if (h.tir) h.skyRefracted = h.skyReflected;

    h.reflected.value = h.local;
    if (!effects.y) {
        h.reflected.value = h.skyReflected;
    } else if (traceM) {
        h.reflected.traced = true;
        h.reflected.ray = PendingRay(offsetRayOrigin(s.position, ng), importance * weightM, reflected, depth + 1, vec3(1.0), coneWidth, media);
    }
    h.refracted.value = h.local;
    if (h.tir) {
        h.refracted.value = h.reflected.value;
    } else if (!effects.z) {
        h.refracted.value = h.skyRefracted;
    } else if (traceR) {
        h.refracted.traced = true;
        MediumStack inside = media;
        if (!(side.entering ? mediumEnter(inside, s.object, s.material) : mediumLeave(inside, s.object))) ++countMediumErrors;
        h.refracted.ray = PendingRay(offsetRayOrigin(s.position, -ng), importance * weightR, refracted, depth + 1, vec3(1.0), coneWidth, inside);
    }
    return h;
}

// The radiance along `root` and the rays it spawns, iterated with the stack; `root` is traced.
// Camera rays (depth 0) trace the effects frame.effects selects at their first hit.
vec3 traceTree(PendingRay root) {
    const bool rayCones = frame.settings.w != 0.0;
    const bool walewski = frame.settings.y != 0.0;
    stack[0] = root;
    int top = 1;
    vec3 L = vec3(0.0);
    while (top > 0) {
        PendingRay ray = stack[--top];
        traceRayEXT(topLevel, gl_RayFlagsOpaqueEXT, 0xFF, kRadianceRay, 0, kRadianceRay, ray.origin, 0.0, ray.direction, 3.0e38, 0);
        if (hit.t < 0.0) {
            if (ray.media.size > 0) ++countMediumErrors;  // left the scene inside a closed object: an open mesh
            L += ray.throughput * skyRadiance(ray.direction);
            continue;
        }
        Surface s = resolveHit();
        // Beer-Lambert absorption of the media the segment ran through (WhittedTracer::radianceAtHit).
        vec3 throughput = mediumAbsorbs(ray.media) ? ray.throughput * segmentTransmittance(ray.media.absorption, hit.t) : ray.throughput;
        // Per-effect tracing applies at the first hit; deeper hits trace everything (TracedEffects).
        bvec3 effects = ray.depth == 0 ? bvec3(frame.effects.xyz != uvec3(0u)) : bvec3(true);
        // The cone at the hit (RayCone::at); none without ray cones (texture_filter = "none").
        float coneWidth = rayCones ? ray.coneWidth + frame.cone.y * hit.t : 0.0;
        HitShading h = shadeHit(s, materials[s.material], ray.direction, ray.depth, ray.importance, coneWidth, ray.media, effects, false,
                                vec3(0.0), true);
        if (!h.composes) {
            L += throughput * h.local;
            continue;
        }
        // The composition's weights of M, R and C (compose() is linear in each).
        float om = h.reflectivity, orr = h.transparency;
        float cM = compose(om, orr, vec3(1.0), vec3(0.0), vec3(0.0), walewski).x;
        float cR = compose(om, orr, vec3(0.0), vec3(1.0), vec3(0.0), walewski).x;
        float cC = compose(om, orr, vec3(0.0), vec3(0.0), vec3(1.0), walewski).x;
        if (h.tir) {
            cM += cR;
            cR = 0.0;
        }
        L += throughput * cC * h.local;
        if (cM > 0.0) {
            if (h.reflected.traced) {
                ++countReflection;
                PendingRay next = h.reflected.ray;
                next.throughput = throughput * cM;
                stack[top++] = next;
            } else {
                L += throughput * cM * h.reflected.value;
            }
        }
        if (cR > 0.0) {
            if (h.refracted.traced) {
                ++countRefraction;
                PendingRay next = h.refracted.ray;
                next.throughput = throughput * cR;
                stack[top++] = next;
            } else {
                L += throughput * cR * h.refracted.value;
            }
        }
    }
    return L;
}

// The per-pixel counts of the invocation, added to the launch's counters (rayCounts).
void addRayCounts() {
    if (countShadow > 0u) atomicAdd(rayCounts[1], countShadow);
    if (countReflection > 0u) atomicAdd(rayCounts[2], countReflection);
    if (countRefraction > 0u) atomicAdd(rayCounts[3], countRefraction);
    if (countMediumErrors > 0u) atomicAdd(rayCounts[4], countMediumErrors);
}

#endif
