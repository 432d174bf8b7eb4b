#pragma once
// What the layered-EM renderer draws for one lens system in one frame (Hakura & Snyder 2001 §5):
// the tessellated lens's front-facing triangles with, per vertex, F G of each term, F G times the
// sky in the term's exit direction (rays that leave to the sky meet no layer: the sky is behind
// the last layer), and per term and layer the cube-map index and level of detail; which two viewpoint samples are
// blended and how; and the GPU pass (layered_em.frag) computed on the CPU, built on rasterizeLens and
// pixelCubeMapLookup as the rendering matrix is, so that A x is what the GPU draws.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/scene/camera.h"
#include "common/scene/scene.h"
#include "techniques/layered_em/em_bake.h"
#include "techniques/layered_em/lens_raster.h"
#include "techniques/layered_em/lens_tessellation.h"
#include "techniques/layered_em/shaders/layered_em_records.h"

namespace hybridlab {

using layered_em_records::kMaxDrawnLayers;  // the layers the GPU pass composites at most

struct LensDrawGeometry {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;  // front-facing from the viewpoint only (back faces culled, as rasterizeLens)
    std::array<std::vector<glm::vec3>, kPathTerms> weights;                    // F G
    std::array<std::vector<glm::vec3>, kPathTerms> skyWeights;                 // F G * sky(exit direction)
    std::array<std::vector<LayerTextureIndex>, kPathTerms> indices;           // [term][layer]: cube-map index and level per vertex
};

// Texture-coordinate generation (§5): the per-vertex attributes of a tessellated lens drawn from
// `camera` into a width x height image with cube maps of `emSize` texels a face side.
LensDrawGeometry lensDrawGeometry(const TessellatedLens& lens, const std::vector<EmLayer>& layers, const Scene& scene,
                                  const Camera& camera, int width, int height, int emSize);

// The viewpoint samples whose images are blended, by their distance to the current view (§6).
struct ViewpointBlend {
    std::size_t a = 0, b = 0;
    float weightA = 1.0f, weightB = 0.0f;
};
// The nearest sample and the next nearest, weighted by the other's distance (weights sum to 1);
// without blending the nearest alone.
ViewpointBlend blendViewpoints(const LayeredEm& em, glm::vec3 eye, bool blend);

// Per term, the layers front to back with "over" on premultiplied RGBA, the sky behind the last
// layer, times F G; the terms summed (one viewpoint sample's image at one pixel).
glm::vec3 compositeLensTerms(const std::array<std::vector<glm::vec4>, kPathTerms>& layerColors,
                             const std::array<glm::vec3, kPathTerms>& weights, const std::array<glm::vec3, kPathTerms>& skyWeights);

// The GPU lens pass computed on the CPU, held equal to it by LayeredEmPass.GpuCompositesLayersSkyAndViewpointsAsTheCpu
// (tests/techniques/layered_em/test_layered_em.cpp) (no occlusion by the rest of the scene): per pixel the lens
// radiance, alpha 1 where the lens covers the pixel, 0 elsewhere.
std::vector<glm::vec4> drawLensOnCpu(const LensDrawGeometry& geometry, const LayeredEm& em, const ViewpointBlend& blend,
                                     const Camera& camera, int width, int height);

}  // namespace hybridlab
