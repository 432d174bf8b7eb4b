#include "techniques/layered_em/viewpoint_samples.h"

#include <cmath>

#include "common/core/input_error.h"

namespace hybridlab {

namespace {

std::vector<Camera> allViewpointSamples(const Scene& scene, glm::vec3 center, const ViewpointSettings& settings) {
    std::vector<Camera> out;
    if (!settings.cameraPath.empty()) {
        const CameraPath* path = scene.findCameraPath(settings.cameraPath);
        if (!path) throw InputError("scene '" + scene.name + "' has no camera path '" + settings.cameraPath + "'");
        for (int f = 0; f < path->frameCount(); f += std::max(1, settings.frameStride)) out.push_back(path->evaluate(path->frameTime(f), scene.camera));
        return out;
    }
    const glm::vec3 eye = scene.camera.position;
    const float radius = settings.radius > 0.0f ? settings.radius : std::hypot(eye.x - center.x, eye.z - center.z);
    const float height = settings.heightSet ? settings.height : eye.y;
    // Start at the scene camera's bearing, so that sample 0 is (near) the default view.
    const float start = std::atan2(eye.x - center.x, eye.z - center.z);
    const int count = std::max(1, static_cast<int>(std::lround(360.0f / settings.stepDegrees)));
    for (int k = 0; k < count; ++k) {
        const float a = start + glm::radians(settings.stepDegrees * static_cast<float>(k));
        Camera c = scene.camera;
        c.position = {center.x + radius * std::sin(a), height, center.z + radius * std::cos(a)};
        c.orientation = Camera::lookAtOrientation(c.position, center);
        out.push_back(c);
    }
    return out;
}

}  // namespace

std::vector<Camera> viewpointSamples(const Scene& scene, glm::vec3 center, const ViewpointSettings& settings) {
    std::vector<Camera> out = allViewpointSamples(scene, center, settings);
    if (settings.maxSamples > 0 && out.size() > static_cast<std::size_t>(settings.maxSamples)) out.resize(static_cast<std::size_t>(settings.maxSamples));
    return out;
}

}  // namespace hybridlab
