#pragma once
// Secondary-ray origins that cannot re-hit their own surface: Wächter & Binder, "A Fast and Robust
// Method for Avoiding Self-Intersection", Ray Tracing Gems (2019), ch. 6. The offset grows with the
// magnitude of the coordinates, so one rule works at every scene scale.
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

namespace hybridlab {

// p offset along the unit geometric normal n (towards the side the new ray leaves from).
inline glm::vec3 offsetRayOrigin(glm::vec3 p, glm::vec3 n) {
    constexpr float kOrigin = 1.0f / 32.0f, kFloatScale = 1.0f / 65536.0f, kIntScale = 256.0f;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        auto ofi = static_cast<std::int32_t>(kIntScale * n[i]);
        auto bits = std::bit_cast<std::int32_t>(p[i]);
        float pi = std::bit_cast<float>(bits + (p[i] < 0.0f ? -ofi : ofi));
        out[i] = std::abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : pi;
    }
    return out;
}

}  // namespace hybridlab
