#include "tests/support/metric_test_images.h"

#include <cmath>

#include "common/image/color.h"

namespace hybridlab::test {

Image fromDisplay(int width, int height, const std::function<glm::vec3(int x, int y)>& display) {
    Image image(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) image.at(x, y) = glm::vec4(srgbToLinear(display(x, y)), 1.0f);
    }
    return image;
}

Image fromDisplay(const cv::Mat3f& display) {
    return fromDisplay(display.cols, display.rows, [&](int x, int y) {
        const cv::Vec3f& c = display(y, x);
        return glm::vec3(c[0], c[1], c[2]);
    });
}

Image flatDisplay(int width, int height, glm::vec3 display) {
    return fromDisplay(width, height, [&](int, int) { return display; });
}

cv::Mat3f displayPattern(int width, int height) {
    cv::Mat3f p(height, width);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float u = static_cast<float>(x) / static_cast<float>(width - 1);
            const float v = static_cast<float>(y) / static_cast<float>(height - 1);
            cv::Vec3f c(0.5f + 0.3f * std::sin(x / 7.0f) * std::cos(y / 11.0f), 0.1f + 0.8f * u, 0.2f + 0.6f * v);
            if (x > width / 8 && x < width / 3 && y > height / 6 && y < height / 2) c = cv::Vec3f(0.95f, 0.9f, 0.7f);
            const float dx = x - 0.7f * width, dy = y - 0.6f * height;
            if (dx * dx + dy * dy < 0.04f * width * width) c = cv::Vec3f(0.05f, 0.1f, 0.3f);
            if (x < width / 5 && y > 3 * height / 4) c = ((x / 3 + y / 3) % 2) ? cv::Vec3f(0.9f, 0.9f, 0.9f) : cv::Vec3f(0.1f, 0.1f, 0.1f);
            p(y, x) = c;
        }
    }
    return p;
}

}  // namespace hybridlab::test
