#include "techniques/technique.h"

#include "common/core/input_error.h"

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

const TechniqueInfo& findTechnique(const std::string& name) {
    std::string known;
    for (const auto& t : registeredTechniques()) {
        if (t.name == name) return t;
        known += (known.empty() ? "" : ", ") + t.name;
    }
    throw InputError("unknown technique '" + name + "' (techniques: " + known + ")");
}

std::unique_ptr<Technique> createTechnique(const std::string& name,
                                           const std::vector<std::pair<std::string, ParamValue>>& parameters) {
    const TechniqueInfo& info = findTechnique(name);
    return info.create(resolveParameters(info.parameters, parameters, "technique " + name));
}

}  // namespace hybridlab
