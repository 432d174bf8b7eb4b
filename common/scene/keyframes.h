#pragma once
// Interpolation of keyframed values, shared by camera paths and rigid object animation.
#include <span>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace hybridlab {

enum class Interpolation { Linear, CatmullRom };

// The segment of sorted key `times` that contains t, and the parameter u in [0, 1] within it;
// t outside the keys clamps to the first or last key.
struct KeySegment {
    std::size_t index = 0;  // segment from key index to key index + 1
    float u = 0.0f;
};
KeySegment findSegment(std::span<const double> times, double t);

// Passes through every key at its time. Catmull-Rom uses non-uniform tangents
// m_i = (p_(i+1) - p_(i-1)) / (t_(i+1) - t_(i-1)) (one-sided at the ends) in a cubic Hermite.
glm::vec3 interpolate(std::span<const double> times, std::span<const glm::vec3> values, double t,
                      Interpolation mode);

// Orientation keys: spherical linear interpolation on the shortest arc (both modes).
glm::quat interpolate(std::span<const double> times, std::span<const glm::quat> values, double t);

}  // namespace hybridlab
