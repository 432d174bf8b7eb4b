#pragma once
// The one shading model (DESIGN.md "The shading model") on the scene's C++ records. The physics
// is written once, for C++ and GLSL, in common/shading (direct_lighting.h: the local colour's
// terms; reflection_refraction.h; composition.h: the composition and the rays of a hit); the
// functions here hand it the scene's materials and lights, and add what only the host does (the
// sky's cube map, the mip chains). All colours are linear.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/image/mip_chain.h"
#include "common/scene/scene.h"
#include "common/shading/composition.h"
#include "common/shading/direct_lighting.h"
#include "common/shading/reflection_refraction.h"

namespace hybridlab {

using shading_language::fresnelDielectric;
using shading_language::LightSample;
using shading_language::reflectDirection;
using shading_language::refractDirection;

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

enum class BlendRule { Design, Walewski2019 };

// The composition rule (composition.h).
inline glm::vec3 compose(float om, float orr, glm::vec3 M, glm::vec3 R, glm::vec3 C, BlendRule rule = BlendRule::Design);

// The local colour C for which compose(om, orr, M, R, C, rule) equals `composite` (both rules are
// affine in C with slope (1 - o_m)(1 - o_r)); `fallback` where that slope is too small for C to
// matter. Recovers the rasterizer's shadow-mapped C from its composed pixel.
inline glm::vec3 uncomposeLocal(float om, float orr, glm::vec3 M, glm::vec3 R, glm::vec3 composite, glm::vec3 fallback,
                                BlendRule rule = BlendRule::Design);

// Sky radiance in a world direction: the cube map (OpenGL face convention) or the constant colour.
glm::vec3 skyRadiance(const Scene& scene, glm::vec3 direction);


// Per-light and per-hit terms, inline: they run for every light at every hit of every ray.

inline DiffuseTexture makeDiffuseTexture(const Material& m, const MipChain* mips) {
    if (!mips) return {};
    const Image& base = mips->level(0);
    return {mips, shading_language::textureUvUnitLod(static_cast<float>(base.width()), static_cast<float>(base.height()), m.textureTiling)};
}

inline glm::vec3 diffuseTextureValue(const Material& m, const DiffuseTexture& texture, glm::vec2 uv, float uvLod) {
    if (!texture.mips) return glm::vec3(1.0f);
    const glm::vec2 t = uv * m.textureTiling + m.textureOffset;
    // The footprint in level-0 texels.
    return glm::vec3(texture.mips->sampleTrilinearWrap(t.x, t.y, uvLod + texture.uvUnitLod));
}

// The light's type as the shaders' records code it (kLight*).
inline std::uint32_t lightTypeCode(Light::Type type) {
    return type == Light::Type::Directional ? raster_records::kLightDirectional
           : type == Light::Type::Point     ? raster_records::kLightPoint
                                            : raster_records::kLightSpot;
}

inline LightSample sampleLight(const Light& light, const SpotCone& cone, glm::vec3 p) {
    return shading_language::sampleLight(lightTypeCode(light.type), light.color * light.intensity, light.position, light.direction,
                                         cone.cosInner, cone.cosOuter, p);
}

inline glm::vec3 blinnPhong(const SurfacePoint& s, glm::vec3 textureValue, glm::vec3 toViewer, const LightSample& light) {
    const Material& m = *s.material;
    return shading_language::blinnPhong(s.normal, m.diffuse * textureValue, m.specular, m.specularExponent, toViewer, light);
}

// Inline, not for the arithmetic but for the call: a vec3 argument assembled from scalars just
// before it is stored apart and reloaded as one, a failed store-to-load forwarding per hit.
inline glm::vec3 unlitTerm(const Scene& scene, const SurfacePoint& s, glm::vec3 textureValue) {
    return shading_language::unlitTerm(s.material->emission, s.material->ambient, scene.ambient, textureValue);
}

inline glm::vec3 occluderTransmittance(const Material& m) {
    return shading_language::occluderTransmittance(m.castsShadows, m.opacity, m.diffuse);
}

inline glm::vec3 compose(float om, float orr, glm::vec3 M, glm::vec3 R, glm::vec3 C, BlendRule rule) {
    return shading_language::compose(om, orr, M, R, C, rule == BlendRule::Walewski2019);
}

inline glm::vec3 uncomposeLocal(float om, float orr, glm::vec3 M, glm::vec3 R, glm::vec3 composite, glm::vec3 fallback, BlendRule rule) {
    return shading_language::uncomposeLocal(om, orr, M, R, composite, fallback, rule == BlendRule::Walewski2019);
}

}  // namespace hybridlab
