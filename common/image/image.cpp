#include "common/image/image.h"

#include <cmath>

namespace hybridlab {

Image::Image(int width, int height, glm::vec4 fill)
    : width_(width), height_(height),
      pixels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill) {}

glm::vec4 Image::sampleBilinearWrap(float u, float v) const {
    // Texel centres sit at half-integer coordinates.
    float x = u * width_ - 0.5f;
    float y = v * height_ - 0.5f;
    float fx = std::floor(x), fy = std::floor(y);
    float tx = x - fx, ty = y - fy;
    auto wrap = [](int i, int n) { int r = i % n; return r < 0 ? r + n : r; };
    int x0 = wrap(static_cast<int>(fx), width_), x1 = wrap(static_cast<int>(fx) + 1, width_);
    int y0 = wrap(static_cast<int>(fy), height_), y1 = wrap(static_cast<int>(fy) + 1, height_);
    glm::vec4 top = at(x0, y0) * (1.0f - tx) + at(x1, y0) * tx;
    glm::vec4 bottom = at(x0, y1) * (1.0f - tx) + at(x1, y1) * tx;
    return top * (1.0f - ty) + bottom * ty;
}

}  // namespace hybridlab
