#pragma once
// One EM layer's texture: a cube map with alpha (faces +X, -X, +Y, -Y, +Z, -Z in the OpenGL
// convention) and its whole MIP map (Hakura & Snyder 2001 §4.3 infer "entire MIPMAPs"),
// premultiplied RGBA, and THE lookup that both the rendering matrix (em_inference.h) and the
// renderer use: which texels a cube-map index and level of detail read and with what weights
// (trilinear: bilinear in the two nearest levels). The renderer's GPU pass must reproduce
// cubeMapLookup exactly (the same face choice, texel-centre convention, bilinear weights and clamp
// at face edges, level blend, then texelFetch), so that A x is what it draws.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/image/cube_map_coordinate.h"
#include "common/image/image.h"

namespace hybridlab {

struct CubeMapTap {
    std::uint32_t texel = 0;  // face * size * size + row * size + column
    float weight = 0.0f;
};

// Taps of one cube-map lookup: four bilinear taps in each of two adjacent levels (weights sum to 1;
// the second level's are zero when the lookup reads one level).
struct CubeMapLookup {
    std::array<CubeMapTap, 8> taps{};
};

// The MIP chain of a cube map with `size` texels a face side: level k has max(1, size >> k) a side,
// down to one texel a face; texels are stored level after level, each level face after face.
int cubeMapLevels(int size);
inline int cubeMapLevelSize(int size, int level) { return std::max(1, size >> level); }
std::size_t cubeMapLevelOffset(int size, int level);  // the level's first texel
inline std::size_t cubeMapTexelCount(int size) { return cubeMapLevelOffset(size, cubeMapLevels(size)); }  // the whole chain

struct CubeMapTexel {
    int level = 0, face = 0, column = 0, row = 0;
};
CubeMapTexel cubeMapTexelAt(std::uint32_t texel, int size);
std::uint32_t cubeMapTexelIndex(const CubeMapTexel& t, int size);

// The chain's tree: per texel, the texel of the next coarser level that covers it (the last
// level's texels have none: kNoParent).
inline constexpr std::uint32_t kNoParent = 0xffffffffu;
std::vector<std::uint32_t> cubeMapParents(int size);

// The level of detail of a lookup whose index turns by `radiansPerPixel` from one pixel to the
// next: log2 of half the pixel's footprint in level-0 texels (a level-0 texel spans 2 / size
// radians at a face's centre), at least 0. Half, not the whole footprint (a level-of-detail bias
// of -1): the reference samples each pixel at its centre without a prefilter, and trilinear
// filtering at the footprint's own level blurs what it resolves (teapot-lens baked at the
// display's 320x180, lens SSIM at the camera / between samples 0.853 / 0.838 -> 0.866 / 0.859;
// a quarter aliases the minified cup). One rule for the renderer's per-vertex levels and the
// direct images.
float cubeMapLod(float radiansPerPixel, int size);

// The lookup: bilinear filtering of a level's texels around the coordinate, texel centres at
// (i + 0.5) / side, clamped to the face (no filtering across faces), in levels floor(lod) and the
// next, blended by lod's fraction (lod clamped to the chain).
CubeMapLookup cubeMapLookup(glm::vec3 direction, int size, float lod = 0.0f);

// The direction through the centre of a texel of any level (unit).
glm::vec3 cubeMapTexelDirection(std::uint32_t texel, int size);

struct LayerCubeMap {
    int size = 0;
    std::vector<glm::vec4> texels;  // premultiplied RGBA, cubeMapTexelCount(size)

    explicit LayerCubeMap(int s = 0) : size(s), texels(cubeMapTexelCount(s), glm::vec4(0.0f)) {}
    glm::vec4 sample(const CubeMapLookup& l) const {
        glm::vec4 v(0.0f);
        for (const CubeMapTap& t : l.taps) v += t.weight * texels[t.texel];
        return v;
    }
};

// The six faces of a level as a 4 x 3 horizontal cross (-X +Z +X -Z in the middle row, +Y above
// and -Y below +Z), premultiplied RGBA; for looking at inferred EMs.
Image cubeMapCross(const LayerCubeMap& map, int level = 0);

}  // namespace hybridlab
