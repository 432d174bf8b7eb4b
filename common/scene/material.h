#pragma once
// A material as in Walewski 2019 Table 1 and DESIGN.md "The shading model". Colours are linear.
#include <cstdint>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace hybridlab {

inline constexpr std::int32_t kNoTexture = -1;

struct Material {
    std::string name;
    glm::vec3 emission{0.0f};
    glm::vec3 ambient{0.0f};          // times the scene's global ambient colour
    glm::vec3 diffuse{0.8f};          // times the diffuse texture when there is one
    glm::vec3 specular{0.0f};
    float specularExponent = 32.0f;   // Blinn-Phong exponent, in [1, 255] as Walewski Table 1
    float reflectivity = 0.0f;        // o_m in the composition rule
    float ior = 1.5f;                 // index of refraction
    float opacity = 1.0f;             // 1 - o_r
    bool fresnel = false;             // reflectivity follows exact unpolarised Fresnel of the IOR
    glm::vec3 absorption{0.0f};       // per unit length inside thick glass (Hakura & Snyder's G)
    bool castsShadows = true;
    std::int32_t diffuseTexture = kNoTexture;  // index into Scene::textures (sRGB, decoded)
    std::int32_t normalTexture = kNoTexture;   // tangent-space normal map (linear)
    glm::vec2 textureTiling{1.0f};
    glm::vec2 textureOffset{0.0f};

    bool isReflective() const { return reflectivity > 0.0f || fresnel; }
    bool isRefractive() const { return opacity < 1.0f; }
};

}  // namespace hybridlab
