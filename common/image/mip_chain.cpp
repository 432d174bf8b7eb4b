#include "common/image/mip_chain.h"

#include <algorithm>
#include <cmath>

namespace hybridlab {

namespace {

// Bilinear lookup at continuous texel coordinates with clamp-to-edge addressing: what
// vkCmdBlitImage with VK_FILTER_LINEAR reads.
glm::vec4 bilinearClamp(const Image& img, float x, float y) {
    x = std::clamp(x - 0.5f, 0.0f, static_cast<float>(img.width() - 1));
    y = std::clamp(y - 0.5f, 0.0f, static_cast<float>(img.height() - 1));
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const int x1 = std::min(x0 + 1, img.width() - 1), y1 = std::min(y0 + 1, img.height() - 1);
    const float tx = x - static_cast<float>(x0), ty = y - static_cast<float>(y0);
    const glm::vec4 top = img.at(x0, y0) * (1.0f - tx) + img.at(x1, y0) * tx;
    const glm::vec4 bottom = img.at(x0, y1) * (1.0f - tx) + img.at(x1, y1) * tx;
    return top * (1.0f - ty) + bottom * ty;
}

// One blit: every destination texel centre mapped into the source and read bilinearly (a 2 x 2 box
// filter when the source size is even).
Image halve(const Image& src) {
    Image dst(std::max(1, src.width() / 2), std::max(1, src.height() / 2));
    const float sx = static_cast<float>(src.width()) / static_cast<float>(dst.width());
    const float sy = static_cast<float>(src.height()) / static_cast<float>(dst.height());
    for (int y = 0; y < dst.height(); ++y)
        for (int x = 0; x < dst.width(); ++x) dst.at(x, y) = bilinearClamp(src, (static_cast<float>(x) + 0.5f) * sx, (static_cast<float>(y) + 0.5f) * sy);
    return dst;
}

}  // namespace

MipChain::MipChain(const Image& base) : base_(&base) {
    const Image* above = &base;
    while (above->width() > 1 || above->height() > 1) {
        levels_.push_back(halve(*above));
        above = &levels_.back();
    }
}

glm::vec4 MipChain::sampleTrilinearWrap(float u, float v, float lod) const {
    if (!(lod > 0.0f)) return base_->sampleBilinearWrap(u, v);  // also NaN and -inf: no footprint
    const float last = static_cast<float>(levels() - 1);
    if (lod >= last) return level(levels() - 1).sampleBilinearWrap(u, v);
    const int l0 = static_cast<int>(lod);
    const float t = lod - static_cast<float>(l0);
    return level(l0).sampleBilinearWrap(u, v) * (1.0f - t) + level(l0 + 1).sampleBilinearWrap(u, v) * t;
}

}  // namespace hybridlab
