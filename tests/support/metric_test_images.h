#pragma once
// Images for the metric tests, made in display sRGB (what the metrics see) and handed to the
// metrics as linear images, as techniques produce them.
#include <functional>

#include <glm/vec3.hpp>
#include <opencv2/core.hpp>

#include "common/image/image.h"

namespace hybridlab::test {

// A linear image whose display values are display(x, y) (in [0, 1]).
Image fromDisplay(int width, int height, const std::function<glm::vec3(int x, int y)>& display);
Image fromDisplay(const cv::Mat3f& display);

// A flat field of one display colour.
Image flatDisplay(int width, int height, glm::vec3 display);

// A display-space test pattern with smooth gradients, a sinusoid, a bright rectangle, a dark
// disc and a checkerboard corner: edges, flat areas and texture, all within [0.05, 0.95].
cv::Mat3f displayPattern(int width, int height);

}  // namespace hybridlab::test
