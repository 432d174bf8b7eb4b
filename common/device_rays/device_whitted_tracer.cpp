#include "common/device_rays/device_whitted_tracer.h"

#include <algorithm>
#include <cstring>

#include <glm/trigonometric.hpp>

#include "common/raster/vulkan_error.h"
#include "common/raytrace/ray_cone.h"

namespace hybridlab {

using namespace device_rays;

DeviceFrame deviceFrame(const DeviceRayScene& scene, const Camera& camera, int width, int height, const WhittedSettings& s,
                        TracedEffects effects) {
    const Scene& sc = scene.scene();
    DeviceFrame f{};
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    // Camera::rayThroughNdc: orientation * (ndc.x t aspect, -ndc.y t, -1) for perspective cameras,
    // an offset orientation * (ndc.x h aspect, -ndc.y h, 0) for orthographic ones.
    const bool perspective = camera.projection == Camera::Projection::Perspective;
    const float t = perspective ? std::tan(glm::radians(camera.fovYDegrees) * 0.5f) : 0.5f * camera.orthoHeight;
    f.cameraPosition = glm::vec4(camera.position, perspective ? 1.0f : 0.0f);
    f.cameraRight = glm::vec4(camera.orientation * glm::vec3(t * aspect, 0.0f, 0.0f), 0.0f);
    f.cameraUp = glm::vec4(camera.orientation * glm::vec3(0.0f, -t, 0.0f), 0.0f);
    f.cameraForward = glm::vec4(perspective ? camera.orientation * glm::vec3(0.0f, 0.0f, -1.0f) : camera.forward(), 0.0f);
    f.skyColor = glm::vec4(sc.sky.color, sc.sky.hasCubeMap() ? 1.0f : 0.0f);
    f.ambient = glm::vec4(sc.ambient, sc.ambientIor);
    const RayCone cone = s.rayCones ? pixelCone(camera, height) : RayCone{};
    f.cone = glm::vec4(cone.width, cone.spread, 0.0f, 0.0f);
    f.size = glm::ivec4(width, height, static_cast<int>(scene.lightCount()), s.maxDepth);
    f.settings = glm::vec4(s.importanceCutoff, s.blend == BlendRule::Walewski2019 ? 1.0f : 0.0f, s.shadows ? 1.0f : 0.0f,
                           s.rayCones ? 1.0f : 0.0f);
    f.effects = glm::uvec4(effects.shadows, effects.reflection, effects.refraction, 0u);
    f.rules = glm::uvec4(s.depthLimit == DepthLimit::Weighted ? 1u : 0u, 0u, 0u, 0u);
    return f;
}

DeviceWhittedTracer::DeviceWhittedTracer(const DeviceRayScene& scene) : scene_(scene), pipeline_(scene, "device_whitted.rgen") {}

DeviceTraceResult DeviceWhittedTracer::launch(const Camera& camera, int width, int height, const WhittedSettings& settings,
                                              TracedEffects effects) {
    pipeline_.setFrame(deviceFrame(scene_, camera, width, height, settings, effects));
    pipeline_.output(static_cast<VkDeviceSize>(width) * height * sizeof(glm::vec4));
    const DeviceLaunchCounts counts = pipeline_.launch({static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height), "trace"});
    DeviceTraceResult result;
    result.rays = counts.rays;
    result.invocations = counts.invocations;
    result.gpuStages = pipeline_.gpuStages();
    return result;
}

DeviceTraceResult DeviceWhittedTracer::trace(const Camera& camera, int width, int height, const WhittedSettings& settings,
                                             TracedEffects effects) {
    DeviceTraceResult result = launch(camera, width, height, settings, effects);
    const auto* pixels = output().readBack<glm::vec4>(static_cast<std::size_t>(width) * height);
    result.image = Image(width, height);
    std::copy(pixels, pixels + static_cast<std::size_t>(width) * height, result.image.data());
    return result;
}

}  // namespace hybridlab
