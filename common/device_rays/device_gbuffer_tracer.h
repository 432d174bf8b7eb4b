#pragma once
// The hybrids' ray stage on the raster's device: a ray-generation shader over the rasterizer's
// G-buffer and lit image where they lie (shaders/device_gbuffer_rays.glsl), tracing only the
// secondary rays its technique asks for from the texels' surfaces, as GBufferSurface and
// WhittedTracer::shadeParts do on the CPU. The rasterizer must run on the ray-tracing device
// (Rasterizer with DeviceFeatures::rayTracing): no target is copied between devices or to the host.
// The technique's shader writes the frame's image (and per-texel terms for its later passes); the
// host reads back the image, the counters, and what the technique asks for.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "common/device_rays/device_ray_pipeline.h"
#include "common/raster/frame_pass.h"
#include "common/raytrace/ray_stats.h"
#include "common/raytrace/whitted_tracer.h"

#include <glm/vec4.hpp>

namespace hybridlab {

struct DeviceGBufferTrace {
    RayStats rays;                                   // counted on the device
    DeviceInvocations invocations;
    std::array<std::uint32_t, 16> techniqueCounts{};  // the shader's own counters (techniqueCounts)
    std::vector<GpuStageTime> gpuStages;             // "trace", and the technique's pass after it
};

class DeviceGBufferTracer {
public:
    static constexpr std::uint32_t kTexelRecords = 4;  // vec4 per texel in texels() (device_gbuffer_rays.glsl)

    // `raygenShader` includes device_gbuffer_rays.glsl; `classifyShader`, the technique's
    // classification pass (texel_list.glsl), compacts its launches (none: every launch is full).
    DeviceGBufferTracer(const DeviceRayScene& scene, const std::string& raygenShader, const std::string& classifyShader = {});

    const VulkanDevice& device() const { return pipeline_.device(); }

    // Compacted launches (the default, where there is a classification pass and the device has
    // indirect launches): the classification pass lists the texels the ray-generation shader
    // must see and writes the others' outputs itself, and the trace is launched over the list
    // alone, so that no invocation is launched only to return. Full launches, one invocation per
    // texel, give the same images (the test DeviceCompactLaunch holds them byte for byte).
    void setCompactLaunch(bool compact) { compact_ = compact; }
    bool compactsLaunches() const { return compact_ && classify_; }

    // Per object, the technique's data (objectData in the shader); uploaded, a few bytes an object.
    void setObjectData(const std::vector<std::uint32_t>& data);
    // SSR's outputs (ssrColor, ssrHit), or none.
    void setSsr(VkImageView color, VkImageView hit) {
        ssrColor_ = color;
        ssrHit_ = hit;
    }

    // Records one launch (compacted or full) over `targets` (the rasterizer's frame, on this
    // device; lighting included) with `settings` into `cb`, a command buffer of the caller's that
    // may hold the rest of the frame; `flags` reach the shader as frame.rules.y. `after` records
    // the technique's pass that reads the output, GPU-timed as `afterStage`.
    void record(VkCommandBuffer cb, const FrameTargets& targets, const WhittedSettings& settings, std::uint32_t flags = 0,
                const std::function<void(VkCommandBuffer)>& after = {}, const std::string& afterStage = {});
    // After the command buffer record() went into completed: the launch's counts and GPU stages.
    DeviceGBufferTrace lastTrace() const;
    // record() in a submission of its own, waited for; lastTrace().
    DeviceGBufferTrace trace(const FrameTargets& targets, const WhittedSettings& settings, std::uint32_t flags = 0,
                             const std::function<void(VkCommandBuffer)>& after = {}, const std::string& afterStage = {});

    // After the launch: the frame's image, vec4 per texel, row-major, copied to the host.
    const GpuBuffer& image() const { return pipeline_.outputOnHost(); }
    // The image and the per-texel records (kTexelRecords vec4 each) where the device writes them:
    // device-local, read by the technique's pass after the trace.
    const GpuBuffer& deviceImage() const { return *image_; }
    const GpuBuffer& texels() const { return texels_; }
    // After the launch, for debug images and statistics only: the per-texel records (16 x
    // kTexelRecords bytes a texel) copied to the host in a submission of their own after the
    // frame's timed work, counted as its diagnostics (DeviceWork), with `alsoCopy`'s copies.
    const glm::vec4* readTexels(const std::function<void(VkCommandBuffer)>& alsoCopy = {});

private:
    const DeviceRayScene& scene_;
    DeviceRayPipeline pipeline_;
    UniqueSampler nearest_;
    GpuBuffer objectData_, texels_, texelsOnHost_, counts_, countsOnHost_;
    UniquePipeline classify_;  // null: full launches only
    GpuBuffer list_;           // TexelListHeader, then the listed texels
    GpuBuffer listHeaderOnHost_;
    bool compact_ = true;
    bool lastCompact_ = false;  // whether the last launch recorded was compacted
    const GpuBuffer* image_ = nullptr;
    VkImageView ssrColor_ = VK_NULL_HANDLE, ssrHit_ = VK_NULL_HANDLE;
};

}  // namespace hybridlab
