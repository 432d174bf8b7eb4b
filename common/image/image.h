#pragma once
// A float RGBA image in row-major order, row 0 at the top (the Vulkan framebuffer convention).
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

namespace hybridlab {

class Image {
public:
    Image() = default;
    Image(int width, int height, glm::vec4 fill = glm::vec4(0.0f));
    // A moved-from image is 0x0, never a size without pixels: code that reuses an image when its
    // size already matches (the rasterizer's read-back) must see that it has to reallocate.
    Image(const Image&) = default;
    Image& operator=(const Image&) = default;
    Image(Image&& other) noexcept : width_(other.width_), height_(other.height_), pixels_(std::move(other.pixels_)) { other.clear(); }
    Image& operator=(Image&& other) noexcept {
        if (this != &other) {
            width_ = other.width_;
            height_ = other.height_;
            pixels_ = std::move(other.pixels_);
            other.clear();
        }
        return *this;
    }

    int width() const { return width_; }
    int height() const { return height_; }
    bool empty() const { return pixels_.empty(); }
    std::size_t pixelCount() const { return pixels_.size(); }

    glm::vec4& at(int x, int y) { return pixels_[index(x, y)]; }
    const glm::vec4& at(int x, int y) const { return pixels_[index(x, y)]; }
    glm::vec4* data() { return pixels_.data(); }
    const glm::vec4* data() const { return pixels_.data(); }

    // Bilinear lookup with wrap-around addressing; (u, v) = (0, 0) is the top-left corner
    // (glTF's texture-coordinate convention).
    glm::vec4 sampleBilinearWrap(float u, float v) const;

    bool operator==(const Image&) const = default;

private:
    void clear() {
        width_ = height_ = 0;
        pixels_.clear();
    }
    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
    int width_ = 0;
    int height_ = 0;
    std::vector<glm::vec4> pixels_;
};

inline glm::vec4 Image::sampleBilinearWrap(float u, float v) const {
    // Texel centres sit at half-integer coordinates.
    float x = u * width_ - 0.5f;
    float y = v * height_ - 0.5f;
    float fx = std::floor(x), fy = std::floor(y);
    float tx = x - fx, ty = y - fy;
    // i mod n into [0, n): a mask for power-of-two sizes (also for negative i, in two's complement)
    // and no division for an i already inside, since an integer division costs more than the rest
    // of the lookup.
    auto wrap = [](int i, int n) {
        if ((n & (n - 1)) == 0) return i & (n - 1);
        if (static_cast<unsigned>(i) < static_cast<unsigned>(n)) return i;
        int r = i % n;
        return r < 0 ? r + n : r;
    };
    int x0 = wrap(static_cast<int>(fx), width_), x1 = x0 + 1 == width_ ? 0 : x0 + 1;
    int y0 = wrap(static_cast<int>(fy), height_), y1 = y0 + 1 == height_ ? 0 : y0 + 1;
    glm::vec4 top = at(x0, y0) * (1.0f - tx) + at(x1, y0) * tx;
    glm::vec4 bottom = at(x0, y1) * (1.0f - tx) + at(x1, y1) * tx;
    return top * (1.0f - ty) + bottom * ty;
}

}  // namespace hybridlab
