#pragma once
// Object placement: position, Euler rotation in degrees, scale (Walewski 2019 §3).
#include <limits>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace hybridlab {

// Euler angles in degrees, applied about X, then Y, then Z (fixed axes): R = Rz * Ry * Rx.
// POV-Ray's `rotate <x, y, z>` uses the same order, which keeps the export a direct mapping.
glm::quat eulerDegreesToQuat(glm::vec3 degrees);

struct Transform {
    glm::vec3 position{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};

    // M = T * R * S.
    glm::mat4 matrix() const;
};

// Normals transform with the inverse transpose of the upper 3x3.
glm::mat3 normalMatrix(const glm::mat4& m);

struct Aabb {
    glm::vec3 lo{std::numeric_limits<float>::max()};
    glm::vec3 hi{std::numeric_limits<float>::lowest()};

    bool valid() const { return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z; }
    void extend(glm::vec3 p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    void extend(const Aabb& b) { if (b.valid()) { extend(b.lo); extend(b.hi); } }
    glm::vec3 center() const { return 0.5f * (lo + hi); }
    glm::vec3 extent() const { return hi - lo; }
    // Bounds of the eight transformed corners.
    Aabb transformed(const glm::mat4& m) const;
};

}  // namespace hybridlab
