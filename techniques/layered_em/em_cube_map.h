#pragma once
// One EM layer's texture: a cube map with alpha (faces +X, -X, +Y, -Y, +Z, -Z in the OpenGL
// convention), premultiplied RGBA, and THE lookup that both the rendering matrix (em_inference.h)
// and the renderer use: which texels a cube-map index reads and with what weights. The renderer's
// GPU pass must reproduce cubeMapLookup exactly (the same face choice, texel-centre convention,
// bilinear weights and clamp at face edges, then texelFetch), so that A x is what it draws.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/image/image.h"

namespace hybridlab {

struct CubeMapTap {
    std::uint32_t texel = 0;  // face * size * size + row * size + column
    float weight = 0.0f;
};

// Bilinear taps of one cube-map lookup (four; weights sum to 1).
struct CubeMapLookup {
    std::array<CubeMapTap, 4> taps{};
};

inline std::size_t cubeMapTexelCount(int size) { return 6u * static_cast<std::size_t>(size) * static_cast<std::size_t>(size); }

// Face and face coordinates (s, t in [0, 1]) of an unnormalised direction (OpenGL table 3.19).
struct CubeMapCoordinate {
    int face = 0;
    glm::vec2 st{0.5f};
};
CubeMapCoordinate cubeMapCoordinate(glm::vec3 direction);

// The lookup: bilinear filtering of the level-0 texels around the coordinate, texel centres at
// (i + 0.5) / size, clamped to the face (no filtering across faces).
CubeMapLookup cubeMapLookup(glm::vec3 direction, int size);

// The direction through the centre of a texel (unit).
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
    glm::vec4 sample(glm::vec3 direction) const { return sample(cubeMapLookup(direction, size)); }
};

// The six faces as a 4 x 3 horizontal cross (-X +Z +X -Z in the middle row, +Y above and -Y below
// +Z), premultiplied RGBA; for looking at inferred EMs.
Image cubeMapCross(const LayerCubeMap& map);

}  // namespace hybridlab
