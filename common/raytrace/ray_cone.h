#pragma once
// Ray cones for texture level of detail (Akenine-Möller et al., "Texture Level of Detail
// Strategies for Real-Time Ray Tracing", Ray Tracing Gems, 2019, ch. 20): every ray carries a cone
// whose width at a hit is the pixel's footprint there, so that the reference filters textures as
// the rasterizer's mip-mapping does. Curvature is ignored (the cone keeps its spread at a bounce).
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "common/scene/camera.h"

namespace hybridlab {

struct RayCone {
    float width = 0.0f;   // at the ray's origin, world units (0 with spread 0: a ray without footprint)
    float spread = 0.0f;  // growth of the width per unit distance (the spread angle, radians)

    RayCone at(float t) const { return {width + spread * t, spread}; }
};

// The cone of a camera ray through one pixel of an image `imageHeight` pixels high (the
// spread angle atan(2 tan(fov_y / 2) / H)); an orthographic camera's keeps the pixel's width.
inline RayCone pixelCone(const Camera& camera, int imageHeight) {
    const float h = static_cast<float>(imageHeight);
    if (camera.projection == Camera::Projection::Orthographic) return {camera.orthoHeight / h, 0.0f};
    return {0.0f, std::atan(2.0f * std::tan(glm::radians(camera.fovYDegrees) * 0.5f) / h)};
}

// log2 of the footprint's extent in uv units at a hit: the chapter's level of detail
// Delta_0 + log2 |W| - log2 |n . d| without the texture's size (diffuseTextureValue adds it), with
// Delta_0 = uvDensityLod the triangle's 0.5 log2(uv area / world area). -inf without a footprint.
inline float uvFootprintLod(float uvDensityLod, const RayCone& coneAtHit, glm::vec3 direction, glm::vec3 geometricNormal) {
    if (coneAtHit.width <= 0.0f) return -std::numeric_limits<float>::infinity();
    const float cosine = std::max(std::abs(glm::dot(direction, geometricNormal)), 1e-4f);
    return uvDensityLod + std::log2(coneAtHit.width / cosine);
}

}  // namespace hybridlab
