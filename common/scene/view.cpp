#include "common/scene/view.h"

#include "common/core/input_error.h"

namespace hybridlab {

View resolveView(const Scene& scene, const std::string& cameraPath, std::optional<int> frame, std::optional<double> time) {
    if (frame && time) throw InputError("give a frame or a time, not both");
    View v;
    if (cameraPath.empty()) {
        if (frame) throw InputError("a frame number needs a camera path (--camera-path)");
        v.camera = scene.camera;
        v.time = time.value_or(0.0);
        v.label = "camera";
        return v;
    }
    const CameraPath* path = scene.findCameraPath(cameraPath);
    if (!path) {
        std::string known;
        for (const auto& p : scene.cameraPaths) known += (known.empty() ? "" : ", ") + p.name;
        throw InputError("scene " + scene.name + " has no camera path '" + cameraPath + "'" +
                         (known.empty() ? " (it has none)" : " (paths: " + known + ")"));
    }
    if (frame) {
        if (*frame < 0 || *frame >= path->frameCount()) {
            throw InputError("frame " + std::to_string(*frame) + " is outside camera path '" + cameraPath + "' (frames 0 to " +
                             std::to_string(path->frameCount() - 1) + ")");
        }
        v.time = path->frameTime(*frame);
        v.label = cameraPath + "@" + std::to_string(*frame);
    } else {
        v.time = time.value_or(path->startTime());
        v.label = cameraPath + "@t=" + std::to_string(v.time);
    }
    try {
        v.camera = path->evaluate(v.time, scene.camera);
    } catch (const InputError& e) {
        throw InputError(scene.file.string() + ": " + e.what());
    }
    return v;
}

}  // namespace hybridlab
