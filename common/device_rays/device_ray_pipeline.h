#pragma once
// A ray-tracing pipeline over a DeviceRayScene: one ray-generation shader with the backend's
// shared hit and miss programs (radiance closest-hit and miss, shadow any-hit and miss;
// shaders/device_rays.glsl), its descriptor set, shader binding table, per-launch uniforms, ray
// counters and GPU timer; optionally a second descriptor set of the ray-generation shader's own
// inputs (the G-buffer tracer's). The Whitted tracer, the G-buffer tracer and the benchmark's ray
// replay are its users.
#include <array>
#include <functional>
#include <memory>
#include <string>

#include "common/device_rays/device_ray_scene.h"
#include "common/raster/gpu_timer.h"
#include "common/raster/pipelines.h"

namespace hybridlab {

// The compiled pipeline, its layout and shader binding table, shared by every DeviceRayPipeline
// of one ray-generation shader and texture count.
struct CompiledRayPipeline {
    DescriptorSet setLayout;    // owns the set layout the pipeline layout was made with
    DescriptorSet inputLayout;  // set 1's, when the shader has inputs
    UniquePipelineLayout layout;
    UniquePipeline pipeline;
    GpuBuffer bindingTable;
    VkStridedDeviceAddressRegionKHR raygen{}, miss{}, hit{}, callable{};
};

class DeviceRayPipeline {
public:
    // `inputs`: the bindings of set 1, the ray-generation shader's own (none: no set 1).
    DeviceRayPipeline(const DeviceRayScene& scene, const std::string& raygenShader,
                      const std::vector<VkDescriptorSetLayoutBinding>& inputs = {});

    const VulkanDevice& device() const { return device_; }

    // The launch's buffers (rewritten by the caller before launch()): the frame's uniforms, the
    // radiance output (binding 8, resized to `bytes`), the replayed rays (binding 11).
    void setFrame(const device_rays::DeviceFrame& frame) { frame_.write(&frame, sizeof(frame)); }
    const GpuBuffer& output(VkDeviceSize bytes);
    void setReplayRays(GpuBuffer rays);
    // Set 1 (with `inputs` only), written by the caller before launch().
    DescriptorSet& inputs() { return inputs_; }

    // Zeroes the counters, traces a width x height x 1 launch, records `after` (passes that read the
    // trace's output) in the same command buffer, both GPU-timed as `stage`, waits; returns the
    // counters (device_rays.glsl rayCounts). `before` records what the trace needs first (layout
    // transitions of the images it writes), untimed.
    std::array<std::uint32_t, device_rays::kRayCounterCount> launch(std::uint32_t width, std::uint32_t height, const std::string& stage,
                                                                    const std::function<void(VkCommandBuffer)>& after = {},
                                                                    const std::function<void(VkCommandBuffer)>& before = {});
    std::vector<GpuStageTime> gpuStages() const { return timer_.read(); }

private:
    const VulkanDevice& device_;
    std::shared_ptr<const CompiledRayPipeline> program_;
    DescriptorSet descriptors_, inputs_;
    GpuBuffer frame_, counters_, output_, replay_;
    GpuTimer timer_;
};

}  // namespace hybridlab
