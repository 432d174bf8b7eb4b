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

// Pixel coordinates of the tessellation's vertices in a width x height image from `camera`
// (projected once a frame, shared by every term and layer).
std::vector<glm::vec2> lensVertexPixels(const TessellatedLens& lens, const Camera& camera, int width, int height);

// The tessellation's edges that carry one term's level of detail, with their length in pixels:
// both vertices traced, with paths of the term of the same topology, apart on screen. Edges across
// a topology change (a silhouette, a switch between reflection and refraction) are
// discontinuities, not minification, and are left out. Per term, shared by every layer.
struct ScreenEdge {
    std::uint32_t a = 0, b = 0;
    float pixels = 0.0f;
};
std::vector<ScreenEdge> textureLodEdges(const TessellatedLens& lens, PathTerm term, const std::vector<glm::vec2>& pixels);

// The per-vertex level of detail of a layer's lookups (cubeMapLod): over the term's `edges`, the
// angle between the vertices' texture directions over the edge's length on screen, the largest at
// each vertex (as hardware takes the larger screen derivative). Interpolated across triangles like
// every attribute, so the renderer and the rendering matrix read the same levels.
std::vector<float> vertexTextureLods(const std::vector<glm::vec3>& directions, const std::vector<ScreenEdge>& edges, int size);

// One term and layer's per-vertex texture index: what the renderer interpolates and looks up.
struct LayerTextureIndex {
    std::vector<glm::vec3> directions;
    std::vector<float> lods;
};
LayerTextureIndex vertexTextureIndex(const TessellatedLens& lens, PathTerm term, const Shell& shell, const std::vector<ScreenEdge>& edges,
                                     int size);

// Per-vertex F G of one term (what the renderer multiplies the layer lookups by).
std::vector<glm::vec3> vertexPathWeights(const TessellatedLens& lens, PathTerm term);

// A per-vertex attribute interpolated at a covered pixel.
template <typename T>
T interpolateAtPixel(const LensRaster& raster, std::size_t pixel, const std::vector<glm::uvec3>& triangles, const std::vector<T>& attribute) {
    const glm::uvec3& t = triangles[static_cast<std::size_t>(raster.triangle[pixel])];
    const glm::vec3& b = raster.barycentric[pixel];
    return b[0] * attribute[t[0]] + b[1] * attribute[t[1]] + b[2] * attribute[t[2]];
}

// THE per-pixel lookup: the texels and weights a covered pixel reads, from the per-vertex texture
// directions and levels of detail interpolated at the pixel.
CubeMapLookup pixelCubeMapLookup(const LensRaster& raster, std::size_t pixel, const std::vector<glm::uvec3>& triangles,
                                 const LayerTextureIndex& index, int size);

}  // namespace hybridlab
