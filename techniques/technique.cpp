#include "techniques/technique.h"

namespace hybridlab {

double FrameResult::totalMilliseconds() const {
    double t = 0.0;
    for (const auto& s : stages) t += s.milliseconds;
    return t;
}

RayScene& SceneContext::rayScene(double time) {
    if (!rays_) rays_ = std::make_unique<RayScene>(scene_, time, &deformedMeshes_);  // built at `time`: nothing to update yet
    else rays_->setTime(time);
    return *rays_;
}

DeviceRayScene& SceneContext::deviceRayScene(double time) {
    if (!deviceRays_) deviceRays_ = std::make_unique<DeviceRayScene>(VulkanDevice::shared({.rayTracing = true}), scene_, deformedMeshes_, time);
    else deviceRays_->setTime(time);
    return *deviceRays_;
}

Rasterizer& SceneContext::rasterizer(DeviceFeatures features) {
    std::unique_ptr<Rasterizer>& r = features.rayTracing ? rayTracingRasterizer_ : rasterizer_;
    if (!r) r = std::make_unique<Rasterizer>(scene_, &deformedMeshes_, features);
    return *r;
}

}  // namespace hybridlab
