#pragma once
// The one shading model (DESIGN.md "The shading model"). Every technique and the reference call
// these functions; the GLSL lighting pass is their twin. All colours are linear.
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
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "common/scene/scene.h"

namespace hybridlab {

// What local shading needs to know about a surface point.
struct SurfacePoint {
    glm::vec3 position;
    glm::vec3 normal;     // shading normal, unit, facing the viewer
    glm::vec2 uv;
    const Material* material;
};

// Diffuse texture value at a uv, with the material's tiling and offset (bilinear, wrapping);
// 1 when the material has none.
glm::vec3 diffuseTextureValue(const Scene& scene, const Material& m, glm::vec2 uv);

// Radiance arriving at `p` from light `l` ignoring shadows, and the unit direction towards it.
struct LightSample {
    glm::vec3 radiance;
    glm::vec3 toLight;   // unit
    float distance;      // to the light; infinity for directional lights
};
LightSample sampleLight(const Light& light, glm::vec3 p);

// The contribution of one light: E * (diffuse * T * N.L + specular * (N.H)^n), unshadowed.
glm::vec3 blinnPhong(const SurfacePoint& s, glm::vec3 textureValue, glm::vec3 toViewer, const LightSample& light);

// emission + ambient * sceneAmbient * T: the part of C that needs no light.
glm::vec3 unlitTerm(const Scene& scene, const SurfacePoint& s, glm::vec3 textureValue);

// Shadow transmittance through one occluder with this material.
glm::vec3 occluderTransmittance(const Material& m);

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

// Sky radiance in a world direction: the cube map (OpenGL face convention) or the constant colour.
glm::vec3 skyRadiance(const Scene& scene, glm::vec3 direction);

}  // namespace hybridlab
