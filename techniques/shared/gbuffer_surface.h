#pragma once
// A G-buffer texel as the surface a camera ray would have hit there: hybrid techniques start their
// secondary rays from it instead of tracing primary rays (Walewski 2019 §3.3, Listing 8a; de Macedo
// & Rodrigues §III).
#include <glm/geometric.hpp>

#include "common/raster/gbuffer.h"
#include "common/raytrace/ray_cone.h"
#include "common/raytrace/ray_scene.h"
#include "common/scene/camera.h"
#include "common/scene/material.h"

namespace hybridlab {

// The G-buffer targets a GBufferSurface reads.
inline constexpr GBufferTargets kGBufferSurfaceTargets = kGBufferPosition | kGBufferNormal | kGBufferMaterial | kGBufferObjectId;

class GBufferSurface {
public:
    // Texel i of `g` (which holds kGBufferSurfaceTargets) seen by `camera`; not the sky.
    GBufferSurface(const GBuffer& g, std::size_t i, const Camera& camera) : material_(g.materialAt(i)) {
        hit_.position = glm::vec3(g.position[i]);
        hit_.geometricNormal = g.geometricNormal(i);
        hit_.shadingNormal = glm::vec3(g.normal[i]);
        hit_.object = static_cast<std::uint32_t>(g.object(i));
        // The material targets hold textured colours: no texture lookup (diffuseTextureValue gives 1).
        hit_.material = &material_;
        footprint_ = pixelCone(camera, g.height).at(glm::distance(camera.position, hit_.position));
        incoming_ = camera.projection == Camera::Projection::Orthographic ? camera.forward() : glm::normalize(hit_.position - camera.position);
    }
    GBufferSurface(const GBufferSurface&) = delete;  // hit_.material points into this object
    GBufferSurface& operator=(const GBufferSurface&) = delete;

    const SurfaceHit& hit() const { return hit_; }
    // The unit direction of the camera ray to the surface.
    glm::vec3 incoming() const { return incoming_; }
    // The camera ray's cone at the surface (the footprint that secondary rays continue).
    const RayCone& footprint() const { return footprint_; }

private:
    Material material_;
    SurfaceHit hit_;
    glm::vec3 incoming_{0.0f};
    RayCone footprint_;
};

}  // namespace hybridlab
