#version 460
// Deferred lighting (Walewski 2019 §3.1, Listing 5): the local term C of the shading model from
// the G-buffer, every light, with shadow-map visibility when shadows are on, into the P-buffer.
// Where nothing was hit it draws the sky. With environment mapping on (the `raster` technique),
// reflective and refractive pixels look up the sky in the reflected and refracted directions
// (Blinn & Newell 1976) and compose by the shading model, as WhittedTracer::shade does with traced
// rays.
#extension GL_GOOGLE_include_directive : require
#include "shading.glsl"
#include "sky.glsl"

// Pipeline variants (lavapipe runs both sides of every branch, so what a frame does not use is
// compiled out rather than skipped).
layout(constant_id = 0) const bool kShadows = false;             // shadow-map visibility
layout(constant_id = 1) const bool kEnvironmentMapping = false;  // sky in the reflected and refracted directions
layout(constant_id = 2) const bool kWalewskiBlend = false;       // BlendRule::Walewski2019
layout(constant_id = 3) const bool kSkyCubeMap = false;          // the sky is a cube map, not a colour
// Sizes of the light and shadow-layer arrays (at least 1). They are uniform buffers, not storage
// buffers: lavapipe loads uniforms several times faster.
layout(constant_id = 4) const int kLightArraySize = 1;
layout(constant_id = 5) const int kShadowLayerArraySize = 1;

// The records (FrameUniforms, LightData, ShadowLayer) are declared in raster_records.h.
layout(std140, set = 0, binding = 0) uniform Frame { FrameUniforms frame; };


layout(std140, set = 0, binding = 1) uniform Lights { LightData lights[kLightArraySize]; };
layout(std140, set = 0, binding = 2) uniform ShadowLayers { ShadowLayer shadowLayers[kShadowLayerArraySize]; };
layout(set = 0, binding = 3) uniform sampler2DArrayShadow shadowMaps;
layout(set = 0, binding = 4) uniform sampler2DArray skyFaces;  // RGBA32F, read with texelFetch
layout(set = 0, binding = 5) uniform sampler2D gPosition;
layout(set = 0, binding = 6) uniform sampler2D gNormal;
layout(set = 0, binding = 7) uniform sampler2D gEmission;
layout(set = 0, binding = 8) uniform sampler2D gAmbient;
layout(set = 0, binding = 9) uniform sampler2D gDiffuse;
layout(set = 0, binding = 10) uniform sampler2D gSpecular;
layout(set = 0, binding = 11) uniform sampler2D gOptical;
layout(set = 0, binding = 12) uniform usampler2D gObjectId;

layout(location = 0) out vec4 outColor;

// As skyRadiance() (C++): the cube map, or the constant colour.
vec3 skyRadiance(vec3 d) {
    if (!kSkyCubeMap) return frame.skyColor.rgb;
    return skyCubeRadiance(skyFaces, d);
}

// As Camera::rayThroughNdc's direction for the pixel centre (pixelCenterNdc()).
vec3 cameraRayDirection(vec2 fragCoord) {
    vec2 ndc = fragCoord / vec2(frame.counts.zw) * 2.0 - 1.0;
    if (frame.cameraPosition.w == 0.0) return frame.cameraForward.xyz;
    return normalize(ndc.x * frame.cameraRight.xyz - ndc.y * frame.cameraUp.xyz + frame.cameraForward.xyz);
}

// One depth comparison, bilinearly filtered by hand from the 2 x 2 texels a linear filter would use
// (textureGather of comparisons: lavapipe cannot filter D32 linearly).
float filteredComparison(vec2 uv, float layer, float depth, vec2 size) {
    vec4 c = textureGather(shadowMaps, vec3(uv, layer), depth);  // (i0, j1), (i1, j1), (i1, j0), (i0, j0)
    vec2 f = fract(uv * size - 0.5);
    return mix(mix(c.w, c.z, f.x), mix(c.x, c.y, f.x), f.y);
}

// Shadow-map visibility of light `light` at p (normal n facing the viewer): the light's layer (the
// cube face for point lights), a normal offset of a few texels against acne, and PCF over a
// (2r + 1)^2 footprint of filtered comparisons.
float shadowVisibility(LightData light, vec3 p, vec3 n) {
    if (light.shadow.x < 0) return 1.0;
    int layer = light.shadow.x;
    if (light.shadow.y == 6) {
        vec3 v = p - light.position.xyz, a = abs(v);
        int face = a.x >= a.y && a.x >= a.z ? (v.x > 0.0 ? 0 : 1) : (a.y >= a.z ? (v.y > 0.0 ? 2 : 3) : (v.z > 0.0 ? 4 : 5));
        layer += face;
    }
    ShadowLayer s = shadowLayers[layer];
    float texel = s.params.x * (s.params.y > 0.0 ? distance(p, light.position.xyz) : 1.0);
    vec4 clip = s.viewProj * vec4(p + n * (frame.shadowParams.y * texel), 1.0);
    if (clip.w <= 0.0) return 1.0;
    vec3 ndc = clip.xyz / clip.w;
    if (ndc.z <= 0.0) return 1.0;  // beyond the far plane: nothing there casts
    vec2 uv = ndc.xy * 0.5 + 0.5;
    vec2 size = vec2(textureSize(shadowMaps, 0).xy);
    int r = int(frame.shadowParams.x);
    float lit = 0.0;
    for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) lit += filteredComparison(uv + vec2(dx, dy) / size, float(layer), ndc.z, size);
    return lit / float((2 * r + 1) * (2 * r + 1));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec3 incoming = cameraRayDirection(gl_FragCoord.xy);
    if (texelFetch(gObjectId, pixel, 0).r == 0u) {
        outColor = vec4(skyRadiance(incoming), 1.0);
        return;
    }
    vec3 p = texelFetch(gPosition, pixel, 0).xyz;
    vec4 normalAndFacing = texelFetch(gNormal, pixel, 0);
    bool entering = normalAndFacing.w > 0.0;
    // Work on the side the viewer sees, as WhittedTracer::shade.
    vec3 n = entering ? normalAndFacing.xyz : -normalAndFacing.xyz;
    vec3 diffuse = texelFetch(gDiffuse, pixel, 0).rgb;
    vec4 specular = texelFetch(gSpecular, pixel, 0);
    vec3 toViewer = -incoming;

    // As WhittedTracer::localColor, with shadow maps in place of shadow rays.
    // The G-buffer's ambient colour is textured already (T = 1 here).
    vec3 c = unlitTerm(texelFetch(gEmission, pixel, 0).rgb, texelFetch(gAmbient, pixel, 0).rgb, frame.sceneAmbient.rgb, vec3(1.0));
    for (uint i = 0u; i < frame.counts.x; ++i) {
        LightSample ls = sampleLightRecord(lights[i], p);
        vec3 direct = blinnPhong(n, diffuse, specular.rgb, specular.a, toViewer, ls);
        if (direct == vec3(0.0)) continue;
        if (kShadows) direct *= shadowVisibility(lights[i], p, n);
        c += direct;
    }

    if (kEnvironmentMapping) {
        // WhittedTracer::shade with the sky standing in for the reflected and refracted rays.
        vec4 optical = texelFetch(gOptical, pixel, 0);
        float n1 = entering ? frame.sceneAmbient.a : optical.y, n2 = entering ? optical.y : frame.sceneAmbient.a;
        // The composition's weights as at a traced hit of depth 0 that traces both rays
        // (composition.h), the sky standing in for each.
        HitScattering e = scatterAtHit(incoming, n, n1, n2, optical.x, optical.w > 0.5, optical.z, 0, 1, false, 1.0, 0.0, true, true);
        if (e.composes) {
            vec3 M = c, R = c;
            if (e.weightM > 0.0) M = skyRadiance(e.reflectedDirection);
            if (e.tir) R = M;
            else if (e.weightR > 0.0) R = skyRadiance(e.refractedDirection);
            c = compose(e.reflectivity, e.transparency, M, R, c, kWalewskiBlend);
        }
    }
    outColor = vec4(c, 1.0);
}
