#pragma once
// Lights (DESIGN.md): directional, point and spot; point and spot fall off with inverse-square
// distance; each may cast shadows or not.
#include <string>

#include <glm/vec3.hpp>

namespace hybridlab {

inline constexpr int kMaxDirectionalLights = 8;
inline constexpr int kMaxPointLights = 32;
inline constexpr int kMaxSpotLights = 32;

struct Light {
    enum class Type { Directional, Point, Spot };

    std::string name;
    Type type = Type::Point;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;        // radiance scale; point and spot: divided by distance^2
    glm::vec3 position{0.0f};      // point, spot
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional, spot: the way the light travels (unit)
    float innerConeDegrees = 20.0f;  // spot: full intensity inside this half-angle
    float outerConeDegrees = 30.0f;  // spot: zero outside this half-angle
    bool castsShadows = true;
};

const char* lightTypeName(Light::Type type);

}  // namespace hybridlab
