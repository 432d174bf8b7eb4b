#include "common/scene/camera_path.h"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "common/core/input_error.h"
#include "common/core/number_check.h"

namespace hybridlab {

int CameraPath::frameCount() const {
    // A small tolerance keeps the last key when duration * fps is integral up to rounding.
    return static_cast<int>(std::floor(duration() * framesPerSecond + 1e-6)) + 1;
}

Camera CameraPath::evaluate(double t, const Camera& lens) const {
    Camera cam = lens;
    cam.position = interpolate(times, positions, t, interpolation);
    const std::string at = "camera path '" + name + "' at " + formatNumber(t) + " s";
    if (keysLookAt) {
        const glm::vec3 target = interpolate(times, targets, t, interpolation);
        // Keys apart from their look_at points can still pass through them between keys.
        if (!(glm::length(target - cam.position) > 0.0f))
            throw InputError(at + ": the camera is at the point it looks at, so it looks nowhere (expected the path's positions "
                                  "and look_at points apart at every time)");
        cam.orientation = Camera::lookAtOrientation(cam.position, target, up);
    } else {
        cam.orientation = interpolate(times, orientations, t);
    }
    if (!cam.placementUsable())
        throw InputError(at + ": the interpolated camera is not finite, or beyond " + formatNumber(limits::kSceneCoordinate) +
                         " from the origin");
    return cam;
}

}  // namespace hybridlab
