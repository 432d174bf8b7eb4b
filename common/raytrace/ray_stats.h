#pragma once
// Rays traced in a frame, by kind.
#include <cstdint>

namespace hybridlab {

struct RayStats {
    std::uint64_t primary = 0;
    std::uint64_t shadow = 0;
    std::uint64_t reflection = 0;
    std::uint64_t refraction = 0;
    // Not rays: paths whose media could not be tracked (medium_stack.h): a ray that left a medium
    // it never entered, entered more than kMediumCapacity, or left the scene inside one.
    std::uint64_t mediumErrors = 0;

    std::uint64_t total() const { return primary + shadow + reflection + refraction; }
    RayStats& operator+=(const RayStats& o) {
        primary += o.primary, shadow += o.shadow, reflection += o.reflection, refraction += o.refraction;
        mediumErrors += o.mediumErrors;
        return *this;
    }
};

}  // namespace hybridlab
