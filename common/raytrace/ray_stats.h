#pragma once
// Rays traced in a frame, by kind.
#include <cstdint>

namespace hybridlab {

struct RayStats {
    std::uint64_t primary = 0;
    std::uint64_t shadow = 0;
    std::uint64_t reflection = 0;
    std::uint64_t refraction = 0;

    std::uint64_t total() const { return primary + shadow + reflection + refraction; }
    RayStats& operator+=(const RayStats& o) {
        primary += o.primary, shadow += o.shadow, reflection += o.reflection, refraction += o.refraction;
        return *this;
    }
};

}  // namespace hybridlab
