#pragma once
// Options of the raster passes that techniques set (kept free of Vulkan headers).
#include <cstdint>

namespace hybridlab {

struct ShadowSettings {
    std::uint32_t resolution = 2048;  // texels per side of every shadow-map layer
    int pcfRadius = 0;                // PCF over (2r + 1)^2 bilinearly filtered comparisons (0: one 2 x 2 bilinear tap)
    float normalOffsetTexels = 1.5f;  // receiver offset along its normal, in shadow-map texels
    float slopeBias = 2.0f;           // slope-scaled depth bias when rendering the maps

    bool operator==(const ShadowSettings&) const = default;
};

struct LightingOptions {
    bool shadows = false;             // shadow-map visibility (else every light is unshadowed)
    bool environmentMapping = false;  // reflective and refractive pixels compose with the sky (the `raster` technique)
    bool walewskiBlend = false;       // composition rule BlendRule::Walewski2019 instead of the shading model's
};

}  // namespace hybridlab
