#pragma once
// The one shading model (DESIGN.md "The shading model"). Every technique and the reference call
// these functions; shaders/shading.glsl (common/raster) computes
// the same in GLSL, held equal by RasterLighting (tests/raster/test_raster_lighting.cpp). All colours are linear.
//
// Local colour at a surface point P with shading normal N, view direction V (towards the eye):
//   C = emission + ambient * sceneAmbient * T
//       + sum over lights l of  vis_l * E_l * ( diffuse * T * max(N.L, 0)
//                                               + specular * max(N.H, 0)^exponent * [N.L > 0] )
// with T the diffuse texture (1 without one), L the unit direction to the light, H = norm(L + V),
// and E_l the light's radiance at P:
//   directional: colour * intensity
//   point:       colour * intensity / d^2
//   spot:        colour * intensity / d^2 * smoothstep(cos outer, cos inner, cos angle to axis)
// vis_l is the shadow transmittance (1 unshadowed; hard shadows; an occluder that casts shadows
// lets (1 - opacity) * diffuse through, its diffuse colour being its tint).
//
// Composition at a hit (reflected radiance M, refracted radiance R):
//   o_m * M + (1 - o_m) * (o_r * R + (1 - o_r) * C)
// with o_m = reflectivity, or the exact unpolarised Fresnel reflectance when the material asks for
// it, and o_r = 1 - opacity. Total internal reflection sends everything to the reflected ray
// (R = M). Walewski 2019 eqs. (5)-(6) average this with the same expression taken in the other
// order; that is the selectable BlendRule::Walewski2019.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/image/mip_chain.h"
#include "common/scene/scene.h"

namespace hybridlab {

// What local shading needs to know about a surface point.
struct SurfacePoint {
    glm::vec3 position;
    glm::vec3 normal;     // shading normal, unit, facing the viewer
    glm::vec2 uv;
    const Material* material;
};

// A material's diffuse texture as lookups read it: the mip chain (null: none) and the level of
// detail of a footprint of one uv unit, 0.5 log2 of the texels it covers (the texture's size times
// the tiling; the rasterizer's gradients are the uv gradients times the tiling). A tracer makes one
// per material, not one a lookup.
struct DiffuseTexture {
    const MipChain* mips = nullptr;
    float uvUnitLod = 0.0f;
};
inline DiffuseTexture makeDiffuseTexture(const Material& m, const MipChain* mips);

// The material's diffuse texture (1 without one) at uv, with its tiling and offset, filtered over a
// footprint of 2^uvLod uv units (ray cones; -inf: a point, level 0's bilinear lookup).
inline glm::vec3 diffuseTextureValue(const Material& m, const DiffuseTexture& texture, glm::vec2 uv, float uvLod);

// Radiance arriving at `p` from light `l` ignoring shadows, and the unit direction towards it.
struct LightSample {
    glm::vec3 radiance;
    glm::vec3 toLight;   // unit
    float distance;      // to the light; infinity for directional lights
};
LightSample sampleLight(const Light& light, glm::vec3 p);

// The cosines of a spot light's inner and outer cone half-angles. A tracer computes them once per
// frame and passes them to the overload below instead of taking two cosines per sample.
struct SpotCone {
    float cosInner = 1.0f;
    float cosOuter = 1.0f;
};
SpotCone spotCone(const Light& light);
inline LightSample sampleLight(const Light& light, const SpotCone& cone, glm::vec3 p);

// The contribution of one light: E * (diffuse * T * N.L + specular * (N.H)^n), unshadowed.
inline glm::vec3 blinnPhong(const SurfacePoint& s, glm::vec3 textureValue, glm::vec3 toViewer, const LightSample& light);

// emission + ambient * sceneAmbient * T: the part of C that needs no light.
inline glm::vec3 unlitTerm(const Scene& scene, const SurfacePoint& s, glm::vec3 textureValue);

// Shadow transmittance through one occluder with this material.
inline glm::vec3 occluderTransmittance(const Material& m);

// Perfect mirror direction of incident direction d about normal n (both unit; d towards surface).
glm::vec3 reflectDirection(glm::vec3 d, glm::vec3 n);

// Snell refraction of unit incident d through unit normal n (n against d) with eta = n1 / n2.
// Returns false on total internal reflection.
bool refractDirection(glm::vec3 d, glm::vec3 n, float eta, glm::vec3& out);

// Exact unpolarised Fresnel reflectance for cos of the incidence angle and n1, n2; 1 under total
// internal reflection. At normal incidence ((n1 - n2) / (n1 + n2))^2.
float fresnelDielectric(float cosIncident, float n1, float n2);

enum class BlendRule { Design, Walewski2019 };

// The composition rule (see top of file).
glm::vec3 compose(float om, float orr, glm::vec3 M, glm::vec3 R, glm::vec3 C, BlendRule rule = BlendRule::Design);

// The local colour C for which compose(om, orr, M, R, C, rule) equals `composite` (both rules are
// affine in C with slope (1 - o_m)(1 - o_r)); `fallback` where that slope is too small for C to
// matter. Recovers the rasterizer's shadow-mapped C from its composed pixel.
glm::vec3 uncomposeLocal(float om, float orr, glm::vec3 M, glm::vec3 R, glm::vec3 composite, glm::vec3 fallback,
                         BlendRule rule = BlendRule::Design);

// Sky radiance in a world direction: the cube map (OpenGL face convention) or the constant colour.
glm::vec3 skyRadiance(const Scene& scene, glm::vec3 direction);


// Per-light and per-hit terms, inline: they run for every light at every hit of every ray.

inline DiffuseTexture makeDiffuseTexture(const Material& m, const MipChain* mips) {
    if (!mips) return {};
    const Image& base = mips->level(0);
    return {mips, 0.5f * std::log2(static_cast<float>(base.width()) * static_cast<float>(base.height()) *
                                   std::abs(m.textureTiling.x * m.textureTiling.y))};
}

inline glm::vec3 diffuseTextureValue(const Material& m, const DiffuseTexture& texture, glm::vec2 uv, float uvLod) {
    if (!texture.mips) return glm::vec3(1.0f);
    const glm::vec2 t = uv * m.textureTiling + m.textureOffset;
    // The footprint in level-0 texels.
    return glm::vec3(texture.mips->sampleTrilinearWrap(t.x, t.y, uvLod + texture.uvUnitLod));
}

inline LightSample sampleLight(const Light& light, const SpotCone& cone, glm::vec3 p) {
    LightSample s;
    const glm::vec3 e = light.color * light.intensity;
    if (light.type == Light::Type::Directional) {
        s.toLight = -light.direction;
        s.distance = std::numeric_limits<float>::infinity();
        s.radiance = e;
        return s;
    }
    glm::vec3 d = light.position - p;
    float d2 = glm::dot(d, d);
    s.distance = std::sqrt(d2);
    s.toLight = d / s.distance;
    s.radiance = e / d2;
    if (light.type == Light::Type::Spot) {
        float cosAngle = glm::dot(-s.toLight, light.direction);
        const float cosOuter = cone.cosOuter, cosInner = cone.cosInner;
        float x = cosInner > cosOuter ? std::clamp((cosAngle - cosOuter) / (cosInner - cosOuter), 0.0f, 1.0f)
                                      : (cosAngle >= cosOuter ? 1.0f : 0.0f);
        s.radiance *= x * x * (3.0f - 2.0f * x);  // smoothstep, as POV-Ray's spotlight falloff
    }
    return s;
}

inline glm::vec3 blinnPhong(const SurfacePoint& s, glm::vec3 textureValue, glm::vec3 toViewer, const LightSample& light) {
    const Material& m = *s.material;
    float nl = glm::dot(s.normal, light.toLight);
    if (nl <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 c = m.diffuse * textureValue * nl;
    if (m.specular != glm::vec3(0.0f)) {  // most matte materials: skip the pow
        glm::vec3 h = glm::normalize(light.toLight + toViewer);
        c += m.specular * std::pow(std::max(glm::dot(s.normal, h), 0.0f), m.specularExponent);
    }
    return light.radiance * c;
}

// Inline, not for the arithmetic but for the call: a vec3 argument assembled from scalars just
// before it is stored apart and reloaded as one, a failed store-to-load forwarding per hit.
inline glm::vec3 unlitTerm(const Scene& scene, const SurfacePoint& s, glm::vec3 textureValue) {
    return s.material->emission + s.material->ambient * scene.ambient * textureValue;
}

inline glm::vec3 occluderTransmittance(const Material& m) {
    if (!m.castsShadows) return glm::vec3(1.0f);
    return (1.0f - m.opacity) * m.diffuse;
}

}  // namespace hybridlab
