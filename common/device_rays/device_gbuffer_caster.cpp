#include "common/device_rays/device_gbuffer_caster.h"

#include "common/device_rays/device_whitted_tracer.h"
#include "common/raster/gpu_image.h"

namespace hybridlab {

namespace {

// Set 1 of device_gbuffer_cast.rgen: the G-buffer's colour targets as storage images, by target bit index.
std::vector<VkDescriptorSetLayoutBinding> targetBindings() {
    std::vector<VkDescriptorSetLayoutBinding> b;
    for (std::uint32_t i = 0; i < GBufferPass::kColorTargets; ++i)
        b.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_RAYGEN_BIT_KHR, nullptr});
    return b;
}

}  // namespace

DeviceGBufferCaster::DeviceGBufferCaster(const DeviceRayScene& scene)
    : scene_(scene), pipeline_(scene, "device_gbuffer_cast.rgen", targetBindings()) {}

void DeviceGBufferCaster::record(VkCommandBuffer cb, const GBufferStorage& targets, const Camera& camera) {
    // The default settings' ray cones: the pixel's cone filters the textures, whatever the
    // technique's texture_filter, as the G-buffer pass mip-maps them (rayCastGBuffer does the same).
    pipeline_.setFrame(deviceFrame(scene_, camera, static_cast<int>(targets.width), static_cast<int>(targets.height), WhittedSettings{}));
    // Rewritten every frame: the rasterizer recreates its targets when the frame size changes.
    for (int i = 0; i < GBufferPass::kColorTargets; ++i)
        pipeline_.inputs().writeImage(i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, targets.views[i], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
    RayLaunch launch{targets.width, targets.height, "gbuffer.rays"};
    launch.readOutput = false;  // it writes the G-buffer's targets, not the radiance output
    launch.before = [&](VkCommandBuffer cb) {
        // Every texel is written: what the last frame left is discarded (from UNDEFINED), and the
        // last frame's readers finish first.
        for (VkImage image : targets.images) {
            transitionImage(cb, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                            VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR, VK_ACCESS_SHADER_WRITE_BIT);
        }
    };
    pipeline_.record(cb, launch);
}

DeviceGBufferCast DeviceGBufferCaster::cast(const GBufferStorage& targets, const Camera& camera) {
    scene_.device().submitAndWait([&](VkCommandBuffer cb) { record(cb, targets, camera); });
    return lastCast();
}

DeviceGBufferCast DeviceGBufferCaster::lastCast() const {
    const DeviceLaunchCounts counts = pipeline_.counts();
    DeviceGBufferCast result;
    result.primaryRays = counts.rays.primary;
    result.invocations = counts.invocations;
    for (const GpuStageTime& s : pipeline_.gpuStages()) result.gpuMilliseconds += s.milliseconds;
    return result;
}

}  // namespace hybridlab
