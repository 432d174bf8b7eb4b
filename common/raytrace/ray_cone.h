#pragma once
// Ray cones for texture level of detail (Akenine-Möller et al., "Texture Level of Detail
// Strategies for Real-Time Ray Tracing", Ray Tracing Gems, 2019, ch. 20): every ray carries a cone
// whose width at a hit is the pixel's footprint there, so that the reference filters textures as
// the rasterizer's mip-mapping does. Curvature is ignored (the cone keeps its spread at a bounce).
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "common/scene/camera.h"
#include "common/shading/ray_geometry.h"

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

// log2 of the footprint's extent in uv units at a hit (common/shading/ray_geometry.h, written once
// for both ray backends); -inf without a footprint.
inline float uvFootprintLod(float uvDensityLod, const RayCone& coneAtHit, glm::vec3 direction, glm::vec3 geometricNormal) {
    return shading_language::uvFootprintLod(uvDensityLod, coneAtHit.width, direction, geometricNormal);
}

}  // namespace hybridlab
