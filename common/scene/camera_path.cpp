#include "common/scene/camera_path.h"

#include <cmath>

namespace hybridlab {

int CameraPath::frameCount() const {
    // A small tolerance keeps the last key when duration * fps is integral up to rounding.
    return static_cast<int>(std::floor(duration() * framesPerSecond + 1e-6)) + 1;
}

Camera CameraPath::evaluate(double t, const Camera& lens) const {
    Camera cam = lens;
    cam.position = interpolate(times, positions, t, interpolation);
    if (keysLookAt) {
        cam.orientation = Camera::lookAtOrientation(cam.position, interpolate(times, targets, t, interpolation), up);
    } else {
        cam.orientation = interpolate(times, orientations, t);
    }
    return cam;
}

}  // namespace hybridlab
