// Secondary rays from the G-buffer where it lies (the hybrids' ray stage on the raster's device):
// the rasterizer's targets read as images of set 1, a texel taken as the surface a camera ray
// would have hit there (as GBufferSurface, techniques/shared/gbuffer_surface.h), whose ray tree
// (device_whitted_tree.glsl) the hybrids' per-texel shading (heuristic_texel.h, ssr_texel.h,
// written once for both backends) splits into the terms they blend (HitParts).
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

// A hit's terms composed (ShadingParts::composed).
vec3 composed(HitParts p) { return composedParts(p, frame.settings.y != 0.0); }

#endif
