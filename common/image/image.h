#pragma once
// A float RGBA image in row-major order, row 0 at the top (the Vulkan framebuffer convention).
#include <cstddef>
#include <vector>

#include <glm/vec4.hpp>

namespace hybridlab {

class Image {
public:
    Image() = default;
    Image(int width, int height, glm::vec4 fill = glm::vec4(0.0f));

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
    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
    int width_ = 0;
    int height_ = 0;
    std::vector<glm::vec4> pixels_;
};

}  // namespace hybridlab
