#pragma once
// Per-scene state that techniques share: the scene, and the ray-tracing scene and the rasterizer
// built on first use (DESIGN.md: the RayScene is built once per scene), and the deformed vertices
// they share.
#include <memory>

#include "common/device_rays/device_ray_scene.h"
#include "common/raster/rasterizer.h"
#include "common/raytrace/ray_scene.h"
#include "common/scene/scene.h"

namespace hybridlab {

class SceneContext {
public:
    explicit SceneContext(const Scene& scene) : scene_(scene), deformedMeshes_(scene) {}

    const Scene& scene() const { return scene_; }

    // Built at first call (time recorded in rayScene().buildMilliseconds()), then moved to `time`.
    RayScene& rayScene(double time);

    // Created at first call (uploads the scene to the GPU); throws VulkanUnavailable without a device.
    // With `features.rayTracing`, a rasterizer of its own on the ray-tracing device, the one
    // deviceRayScene() is on: a hybrid's frame with rays = "vulkan" stays on that device.
    Rasterizer& rasterizer(DeviceFeatures features = {});

    // The scene on the ray-tracing Vulkan device (techniques with rays = "vulkan"): built at first
    // call (on VulkanDevice::shared({.rayTracing = true})), then moved to `time`. Throws
    // VulkanUnavailable when the device has no ray tracing.
    DeviceRayScene& deviceRayScene(double time);

private:
    const Scene& scene_;
    // Shared by the ray scene and the rasterizer: a hybrid frame deforms each object once.
    DeformedMeshCache deformedMeshes_;
    std::unique_ptr<RayScene> rays_;
    std::unique_ptr<Rasterizer> rasterizer_, rayTracingRasterizer_;
    std::unique_ptr<DeviceRayScene> deviceRays_;
};

}  // namespace hybridlab
