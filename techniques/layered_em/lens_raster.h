#pragma once
// CPU rasterisation of the tessellated lens (Hakura & Snyder 2001 §5): which triangle covers each
// pixel centre and its perspective-correct barycentrics, as the GPU rasteriser computes them
// (Vulkan clip space, y down, pixel centres at +0.5, top-left fill rule, back faces culled, the
// nearest surface kept). The rendering matrix is built from it; the part-2 renderer draws the same
// triangles with the same per-vertex attributes on the GPU.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "common/scene/camera.h"
#include "techniques/layered_em/em_cube_map.h"
#include "techniques/layered_em/layer_shells.h"
#include "techniques/layered_em/lens_tessellation.h"

namespace hybridlab {

struct LensRaster {
    int width = 0, height = 0;
    std::vector<std::int32_t> triangle;   // per pixel: index into the triangles, -1 uncovered
    std::vector<glm::vec3> barycentric;   // per pixel: perspective-correct weights of its vertices

    bool covered(std::size_t pixel) const { return triangle[pixel] >= 0; }
};

LensRaster rasterizeLens(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
                         const Camera& camera, int width, int height);

// The per-vertex cube-map index of one term and layer: the vertex's outgoing ray met with the
// layer's impostor (§5). Vertices without that path (not traced, or the term does not exist) get
// their normal: their F G weight is zero, so what they index does not show.
std::vector<glm::vec3> vertexTextureDirections(const TessellatedLens& lens, PathTerm term, const Shell& shell);

// Per-vertex F G of one term (what the renderer multiplies the layer lookups by).
std::vector<glm::vec3> vertexPathWeights(const TessellatedLens& lens, PathTerm term);

// THE per-pixel lookup: the texels and weights a covered pixel reads, from the per-vertex texture
// directions interpolated at the pixel.
CubeMapLookup pixelCubeMapLookup(const LensRaster& raster, std::size_t pixel, const std::vector<glm::uvec3>& triangles,
                                 const std::vector<glm::vec3>& vertexDirections, int size);

// A per-vertex attribute interpolated at a covered pixel.
glm::vec3 interpolateAtPixel(const LensRaster& raster, std::size_t pixel, const std::vector<glm::uvec3>& triangles,
                             const std::vector<glm::vec3>& attribute);

}  // namespace hybridlab
