#pragma once
// The deformed vertices of a scene's deforming objects, computed once a frame for the two
// consumers that need them: the rasterizer's vertex upload (GpuScene) and the ray scenes' refits
// (RayScene, DeviceRayScene). The first consumer to ask for an object at a time deforms it (deformMesh); the other
// takes the result. A consumer asking again, for its next frame, deforms again, even at the same
// time: a timed repeat of a frame pays the deformation a new frame pays (ray_scene.h, gpu_scene.h).
#include <cstdint>
#include <vector>

#include "common/scene/deformation.h"
#include "common/scene/scene.h"

namespace hybridlab {

class DeformedMeshCache {
public:
    enum Consumer : std::uint8_t { kRasterizer = 1u, kRayScene = 2u, kDeviceRays = 4u };

    explicit DeformedMeshCache(const Scene& scene) : scene_(scene), objects_(scene.objects.size()) {}

    // The meshes of deforming object `object` (in SceneObject::meshes order) at `time`.
    const std::vector<DeformedVertices>& vertices(std::size_t object, double time, Consumer consumer);

    // Objects deformed so far (a frame that both consumers draw adds one per deforming object).
    std::size_t deformations() const { return deformations_; }

private:
    struct Entry {
        double time = 0.0;
        std::uint8_t served = 0;  // consumers that took `meshes` since they were computed
        std::vector<DeformedVertices> meshes;
    };

    const Scene& scene_;
    std::vector<Entry> objects_;
    std::size_t deformations_ = 0;
};

}  // namespace hybridlab
