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
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/device_rays/device_ray_scene.h"
#include "common/raster/gpu_timer.h"
#include "common/raster/pipelines.h"
#include "common/raytrace/ray_stats.h"

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

// A launch's invocations, counted on the device: rays per launched invocation, and how many of
// them were launched only to return.
struct DeviceInvocations {
    std::uint64_t launched = 0;
    std::uint64_t tracing = 0;  // of those, the ones that traced a ray
    std::optional<std::uint64_t> listed;  // a compacted launch: the texels its classification listed
};

// What a launch counted on the device (device_frame.glsl's rayCounts).
struct DeviceLaunchCounts {
    RayStats rays;
    DeviceInvocations invocations;
};

// One launch of width x height invocations and what its command buffer records around it.
struct RayLaunch {
    std::uint32_t width = 0, height = 0;
    std::string stage;  // the trace's GPU stage
    // Recorded first, untimed: what the trace needs (layout transitions of the images it writes).
    std::function<void(VkCommandBuffer)> before;
    // A compacted launch: `classify`, recorded before the trace and GPU-timed as `classifyStage`,
    // writes the launch's size (a VkTraceRaysIndirectCommandKHR) at device address `indirect`, and
    // the trace is launched from it (the device must have traceRaysIndirect()); width and height
    // then only bound it.
    std::function<void(VkCommandBuffer)> classify;
    std::string classifyStage;
    VkDeviceAddress indirect = 0;
    // Recorded after the trace: passes that read its output, GPU-timed as `afterStage`.
    std::function<void(VkCommandBuffer)> after;
    std::string afterStage;
    // Recorded last, untimed, after a barrier that makes every write before it visible to
    // transfers: the caller's copies of what the host reads back (made visible to the host after).
    std::function<void(VkCommandBuffer)> readBack;
    // Whether the radiance output is copied to the host (outputOnHost()).
    bool readOutput = true;
};

class DeviceRayPipeline {
public:
    // `inputs`: the bindings of set 1, the ray-generation shader's own (none: no set 1).
    DeviceRayPipeline(const DeviceRayScene& scene, const std::string& raygenShader,
                      const std::vector<VkDescriptorSetLayoutBinding>& inputs = {});

    const VulkanDevice& device() const { return device_; }

    // The launch's buffers (rewritten by the caller before launch()): the frame's uniforms, the
    // radiance output (binding 8, resized to `bytes`; device-local), the replayed rays (binding 11).
    void setFrame(const device_rays::DeviceFrame& frame) { frame_.write(&frame, sizeof(frame)); }
    const GpuBuffer& output(VkDeviceSize bytes);
    // After launch() (with readOutput): the radiance output's copy on the host, as many bytes.
    const GpuBuffer& outputOnHost() const { return outputOnHost_; }
    void setReplayRays(GpuBuffer rays);
    // Set 1 (with `inputs` only), written by the caller before launch().
    DescriptorSet& inputs() { return inputs_; }
    // The pipeline layout (sets 0 and 1, visible to compute shaders too) and its sets bound at
    // `point`: a classification pass reads what the ray-generation shader reads.
    VkPipelineLayout layout() const { return program_->layout; }
    void bindSets(VkCommandBuffer cb, VkPipelineBindPoint point) const;

    // Records `launch` into `cb` (the counters zeroed, before, the trace, after, the copies to the
    // host), in a command buffer of the caller's, which may hold the rest of the frame; what was
    // written before it on the queue is visible to it.
    void record(VkCommandBuffer cb, const RayLaunch& launch);
    // After the command buffer record() went into completed: the counters.
    DeviceLaunchCounts counts() const;
    // record() in a command buffer of its own, submitted and waited for; the counters.
    DeviceLaunchCounts launch(const RayLaunch& launch);
    // After the launch completed: the trace's GPU stage, then the pass after it where there was one.
    std::vector<GpuStageTime> gpuStages() const { return timer_.read(); }

    // What memory each buffer the launch's rays read lives in (the scene's and the pipeline's), by
    // name: its type's property flags (VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, ...).
    std::vector<std::pair<std::string, VkMemoryPropertyFlags>> bufferMemory() const;

private:
    const DeviceRayScene& scene_;
    const VulkanDevice& device_;
    std::shared_ptr<const CompiledRayPipeline> program_;
    DescriptorSet descriptors_, inputs_;
    GpuBuffer frame_, replay_;
    // Written by the shaders in device memory (on a discrete GPU, not across the bus); copied to
    // the host at the end of each launch.
    GpuBuffer counters_, countersOnHost_, output_, outputOnHost_;
    GpuTimer timer_;
};

}  // namespace hybridlab
