#pragma once
// A named camera path: keyframes at times, interpolated linearly or by Catmull-Rom, sampled at a
// frame rate. Keys give either position and look-at target, or position and orientation.
#include <string>
#include <vector>

#include "common/scene/camera.h"
#include "common/scene/keyframes.h"

namespace hybridlab {

struct CameraPath {
    std::string name;
    Interpolation interpolation = Interpolation::CatmullRom;
    double framesPerSecond = 30.0;
    bool keysLookAt = true;  // keys hold targets (else orientations)
    glm::vec3 up{0.0f, 1.0f, 0.0f};

    std::vector<double> times;            // strictly increasing
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> targets;       // when keysLookAt
    std::vector<glm::quat> orientations;  // when !keysLookAt

    double startTime() const { return times.front(); }
    double duration() const { return times.back() - times.front(); }
    // Frames 0 .. frameCount() - 1 at startTime() + frame / framesPerSecond.
    int frameCount() const;
    double frameTime(int frame) const { return startTime() + frame / framesPerSecond; }

    // The camera at time t: `lens` supplies projection, field of view and clip planes.
    Camera evaluate(double t, const Camera& lens) const;
};

}  // namespace hybridlab
