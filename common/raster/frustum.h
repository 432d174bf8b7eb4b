#pragma once
// View-frustum culling of world-space boxes against a Vulkan clip matrix (depth in [0, 1]).
#include <array>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "common/scene/transform.h"

namespace hybridlab {

class Frustum {
public:
    // The six planes -w <= x <= w, -w <= y <= w, 0 <= z <= w of clip = viewProj * p (Gribb & Hartmann).
    explicit Frustum(const glm::mat4& viewProj) {
        const glm::vec4 r0(viewProj[0][0], viewProj[1][0], viewProj[2][0], viewProj[3][0]);
        const glm::vec4 r1(viewProj[0][1], viewProj[1][1], viewProj[2][1], viewProj[3][1]);
        const glm::vec4 r2(viewProj[0][2], viewProj[1][2], viewProj[2][2], viewProj[3][2]);
        const glm::vec4 r3(viewProj[0][3], viewProj[1][3], viewProj[2][3], viewProj[3][3]);
        planes_ = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2};
    }

    // False only when the box lies wholly outside one plane (conservative).
    bool intersects(const Aabb& box) const {
        if (!box.valid()) return false;
        for (const glm::vec4& p : planes_) {
            const glm::vec3 farthest(p.x >= 0.0f ? box.hi.x : box.lo.x, p.y >= 0.0f ? box.hi.y : box.lo.y,
                                     p.z >= 0.0f ? box.hi.z : box.lo.z);
            if (p.x * farthest.x + p.y * farthest.y + p.z * farthest.z + p.w < 0.0f) return false;
        }
        return true;
    }

private:
    std::array<glm::vec4, 6> planes_;
};

}  // namespace hybridlab
