#pragma once
// Keyframed rigid transform of an object (position, rotation, scale), for dynamic scenes.
#include <vector>

#include "common/scene/keyframes.h"
#include "common/scene/transform.h"

namespace hybridlab {

struct RigidAnimation {
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times;  // strictly increasing
    std::vector<glm::vec3> positions;
    std::vector<glm::quat> rotations;
    std::vector<glm::vec3> scales;

    bool empty() const { return times.empty(); }
    Transform at(double t) const;
};

}  // namespace hybridlab
