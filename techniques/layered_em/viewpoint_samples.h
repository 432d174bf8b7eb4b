#pragma once
// The 1D viewpoint subspace of a lens system (Hakura & Snyder 2001 §1, §6): by default a circle
// around the lens centre at a given radius and height sampled every 8 degrees, or the frames of a
// named camera path. Each sample looks at the lens centre (circle) or as the path says.
#include <string>
#include <vector>

#include "common/scene/camera.h"
#include "common/scene/scene.h"

namespace hybridlab {

struct ViewpointSettings {
    std::string cameraPath;       // non-empty: the path's frames (every frameStride-th)
    int frameStride = 1;
    float stepDegrees = 8.0f;     // circle
    float radius = 0.0f;          // circle: horizontal distance from the centre; 0: the scene camera's
    float height = 0.0f;          // circle: world y of the eye; used when heightSet
    bool heightSet = false;       // false: the scene camera's height
    int maxSamples = 0;           // keep only the first n samples (0: all), for quick bakes
    bool closed() const { return cameraPath.empty() && maxSamples == 0; }  // a whole circle wraps around
};

// Throws InputError for an unknown camera path.
std::vector<Camera> viewpointSamples(const Scene& scene, glm::vec3 center, const ViewpointSettings& settings);

}  // namespace hybridlab
