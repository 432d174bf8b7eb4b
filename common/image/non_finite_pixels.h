#pragma once
// Pixels holding a NaN or an infinity. A texture must hold none: filtering would spread one over
// every pixel that samples near it. A rendered image with some is counted and named, never scored
// silently: every metric over it would be NaN.
#include <cmath>
#include <cstddef>
#include <string>

#include <glm/vec4.hpp>

#include "common/image/image.h"

namespace hybridlab {

inline bool isFinitePixel(const glm::vec4& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && std::isfinite(c.a); }

// How many pixels of an image hold a non-finite channel, and the first in row order.
struct NonFinitePixels {
    std::size_t count = 0;
    int x = -1, y = -1;  // the first
    glm::vec4 value{0.0f};

    // "3 non-finite pixels (NaN or infinite), the first at (4, 0): (nan, 0, 0, 1)"; empty for none.
    std::string description(const char* pixelWord = "pixel") const;
};
NonFinitePixels findNonFinite(const Image& image);

// Throws InputError "NAME: N non-finite texels (NaN or infinite), the first at (x, y): (...)"
// when `image` holds any.
void requireFiniteTexels(const Image& image, const std::string& name);

// Makes black (0, 0, 0, 1) in both images every pixel where either is not finite, so that the
// metrics score the rest (SSIM's window would spread a NaN over its neighbours); returns how many
// pixels it changed. Callers count or name them first.
std::size_t blackOutNonFinite(Image& test, Image& reference);

}  // namespace hybridlab
