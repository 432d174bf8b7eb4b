#pragma once
// GPU timestamps around passes (vkCmdWriteTimestamp), read after the frame's submission and turned
// into stage times with the device's timestamp period. On lavapipe they time the CPU threads that
// execute the command buffer; either way they leave out recording and submission overheads, which
// the caller times on the wall clock. Where the device has pipeline-statistics queries, each
// stage also counts its work (primitives in and after clipping, fragment and compute shader
// invocations): numbers that carry over between machines, as times do not.
#include <optional>
#include <string>
#include <vector>

#include "common/raster/vk_unique.h"
#include "common/raster/vulkan_device.h"

namespace hybridlab {

// A pass's work by Vulkan pipeline-statistics query.
struct PipelineStatistics {
    std::uint64_t inputPrimitives = 0;      // primitives the input assembler read
    std::uint64_t clippingPrimitives = 0;   // primitives out of clipping (what is rasterized)
    std::uint64_t fragmentInvocations = 0;  // fragment shader invocations
    std::uint64_t computeInvocations = 0;   // compute shader invocations
};

struct GpuStageTime {
    std::string name;
    double milliseconds = 0.0;
    std::optional<PipelineStatistics> statistics;  // where the device counts them
};

class GpuTimer {
public:
    // `statistics`: count each stage's work where the device can (false: timestamps only).
    GpuTimer(const VulkanDevice& device, std::uint32_t maxStages, bool statistics = true);

    // At the start of a command buffer: forgets the previous frame's stages. `countWork`: count
    // this frame's stages' work where the timer can (false: timestamps only).
    void reset(VkCommandBuffer cb, bool countWork = true);
    void begin(VkCommandBuffer cb, const std::string& stage);
    void end(VkCommandBuffer cb);
    // After the command buffer completed: one entry per begin/end pair, in order.
    std::vector<GpuStageTime> read() const;

private:
    const VulkanDevice& device_;
    UniqueQueryPool pool_;
    UniqueQueryPool statistics_;  // one query a stage; null without pipeline statistics
    std::uint32_t capacity_;
    std::vector<std::string> names_;
    bool counting_ = false;  // this frame's stages count their work
};

}  // namespace hybridlab
