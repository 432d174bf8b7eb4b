#pragma once
// Which camera and scene time a frame is rendered from: the scene's camera, or a camera path at a
// frame number or a time. Shared by `hybridlab render` and the experiment runner.
#include <optional>
#include <string>

#include "common/scene/scene.h"

namespace hybridlab {

struct View {
    Camera camera;
    double time = 0.0;
    std::string label;  // "camera", "orbit@12", "orbit@t=0.5"
};

// Throws InputError for an unknown path (listing the known ones), a frame out of range, or a
// frame without a path.
View resolveView(const Scene& scene, const std::string& cameraPath, std::optional<int> frame, std::optional<double> time);

}  // namespace hybridlab
