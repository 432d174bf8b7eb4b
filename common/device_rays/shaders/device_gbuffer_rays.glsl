// Secondary rays from the G-buffer where it lies (the hybrids' ray stage on the raster's device):
// the rasterizer's targets read as images of set 1, a texel taken as the surface a camera ray
// would have hit there (as GBufferSurface, techniques/shared/gbuffer_surface.h), and its
// ray tree (device_whitted_tree.glsl) split into the terms the hybrids blend (ShadingParts).
#ifndef DEVICE_GBUFFER_RAYS_GLSL
#define DEVICE_GBUFFER_RAYS_GLSL

#include "device_whitted_tree.glsl"
#include "gbuffer_encoding.glsl"

#include "device_gbuffer_inputs.glsl"

// The texel of this invocation: its launch index, one invocation per texel, or in a compacted
// launch (frame.rules.z) the texel the classification pass listed at it.
ivec2 launchTexel() { return frame.rules.z != 0u ? unpackTexel(listedTexels[gl_LaunchIDEXT.x]) : ivec2(gl_LaunchIDEXT.xy); }

// As GBufferSurface and GBuffer::materialAt: the material targets hold textured colours (no
// texture lookup), and no shadow or absorption properties.
Surface gbufferSurface(ivec2 texel, out DeviceMaterial m) {
    vec4 emission = texelFetch(gEmission, texel, 0), ambient = texelFetch(gAmbient, texel, 0);
    vec4 optical = texelFetch(gOptical, texel, 0);
    m.emission = vec4(emission.rgb, 0.0);
    m.ambient = vec4(ambient.rgb, 0.0);
    m.diffuse = vec4(texelFetch(gDiffuse, texel, 0).rgb, 0.0);
    m.specular = texelFetch(gSpecular, texel, 0);
    m.optical = vec4(optical.xyz, optical.w > 0.5 ? 1.0 : 0.0);
    m.absorption = vec4(0.0);
    m.tilingOffset = vec4(1.0, 1.0, 0.0, 0.0);
    m.textures = ivec4(-1);
    Surface s;
    s.position = texelFetch(gPosition, texel, 0).xyz;
    s.geometricNormal = octahedralDecode(emission.w, ambient.w);
    s.shadingNormal = texelFetch(gNormal, texel, 0).xyz;
    s.uv = vec2(0.0);
    s.uvDensityLod = -1.0 / 0.0;
    s.material = kNoAbsorption;
    s.object = uint(gbufferObject(texel));
    return s;
}

// The unit direction of the camera ray to `p` (GBufferSurface::incoming).
vec3 cameraIncoming(vec3 p) { return frame.cameraPosition.w != 0.0 ? normalize(p - frame.cameraPosition.xyz) : frame.cameraForward.xyz; }

// The camera ray's cone width at `p` (GBufferSurface::footprint); 0 without ray cones.
float cameraFootprint(vec3 p) { return frame.settings.w != 0.0 ? frame.cone.x + frame.cone.y * distance(frame.cameraPosition.xyz, p) : 0.0; }

// addRayCounts(), and the invocation counted as one that traced where the texel traced a ray.
void addTexelRayCounts() {
    addRayCounts();
    if (countShadow + countReflection + countRefraction > 0u) countTraced();
}

// As ShadingParts.
struct Parts {
    vec3 local, reflected, refracted;
    float reflectivity, transparency;
    bool composes;
    vec3 skyReflected, skyRefracted;  // EnvironmentTerms
};

vec3 composed(Parts p) { return p.composes ? compose(p.reflectivity, p.transparency, p.reflected, p.refracted, p.local, frame.settings.y != 0.0) : p.local; }

// As WhittedTracer::shadeParts() in the ambient medium: the hit's terms, its secondary rays
// traced with the ray tree. With `composedOnly` (a caller that reads composed() alone, as
// WhittedTracer::shade()), C is shaded only where it weighs.
Parts shadeParts(Surface s, DeviceMaterial m, vec3 incoming, int depth, float importance, float coneWidth, bvec3 effects, bool localGiven,
                 vec3 givenLocal, bool composedOnly) {
    HitShading h = shadeHit(s, m, incoming, depth, importance, coneWidth, ambientMedium(), effects, localGiven, givenLocal, composedOnly);
    Parts p;
    p.local = h.local;
    p.reflectivity = h.reflectivity;
    p.transparency = h.transparency;
    p.composes = h.composes;
    p.skyReflected = h.skyReflected;
    p.skyRefracted = h.skyRefracted;
    // M, then R (under total internal reflection, M again), from one call site of the tree: lavapipe
    // compiles each inlined copy of the loop anew.
    for (int k = 0; k < 2; ++k) {
        HitTerm term = k == 0 ? h.reflected : h.refracted;
        vec3 v = k == 1 && h.tir ? p.reflected : term.value;
        if (term.traced) {
            if (k == 0) ++countReflection;
            else ++countRefraction;
            v = traceTree(term.ray);
        }
        if (k == 0) p.reflected = v;
        else p.refracted = v;
    }
    return p;
}

#endif
