#pragma once
// sRGB transfer functions (IEC 61966-2-1). Lighting is computed in linear light; textures are
// sRGB-encoded and decoded on load; display images are sRGB-encoded.
#include <algorithm>
#include <cmath>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace hybridlab {

inline float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

inline float linearToSrgb(float c) {
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

inline glm::vec3 srgbToLinear(glm::vec3 c) { return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)}; }
inline glm::vec3 linearToSrgb(glm::vec3 c) { return {linearToSrgb(c.r), linearToSrgb(c.g), linearToSrgb(c.b)}; }

// Display value of a linear pixel: clamp to [0, 1], then encode. Alpha is passed through.
inline glm::vec4 linearToDisplay(glm::vec4 c) {
    auto enc = [](float v) { return linearToSrgb(std::clamp(v, 0.0f, 1.0f)); };
    return {enc(c.r), enc(c.g), enc(c.b), std::clamp(c.a, 0.0f, 1.0f)};
}

}  // namespace hybridlab
