#pragma once
// A texture's mip chain as the rasterizer builds it (common/raster/scene_textures.cpp: each level
// a linear blit of the one above, sizes halved and floored, down to 1 x 1), with trilinear lookups
// at a level of detail: the reference filters textures with it at the ray cone's footprint, as the
// rasterizer's sampler does at the pixel's, so that the two differ by rasterization alone and the
// reference does not alias on minified textures.
#include <vector>

#include "common/image/image.h"

namespace hybridlab {

class MipChain {
public:
    // Keeps a pointer to `base` (level 0), which must outlive the chain.
    explicit MipChain(const Image& base);

    int levels() const { return 1 + static_cast<int>(levels_.size()); }
    const Image& level(int i) const { return i == 0 ? *base_ : levels_[static_cast<std::size_t>(i - 1)]; }

    // Trilinear lookup with wrap-around addressing at level of detail `lod` (log2 of the footprint
    // in level-0 texels): magnified (lod <= 0) is level 0's bilinear lookup; past the last level, the
    // last level's.
    glm::vec4 sampleTrilinearWrap(float u, float v, float lod) const;

private:
    const Image* base_;
    std::vector<Image> levels_;  // 1, 2, ...
};

}  // namespace hybridlab
