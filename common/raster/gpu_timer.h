#pragma once
// GPU timestamps around passes (vkCmdWriteTimestamp), read after the frame's submission and turned
// into stage times with the device's timestamp period. On lavapipe they time the CPU threads that
// execute the command buffer; either way they leave out recording and submission overheads, which
// the caller times on the wall clock.
#include <string>
#include <vector>

#include "common/raster/vk_unique.h"
#include "common/raster/vulkan_device.h"

namespace hybridlab {

struct GpuStageTime {
    std::string name;
    double milliseconds = 0.0;
};

class GpuTimer {
public:
    GpuTimer(const VulkanDevice& device, std::uint32_t maxStages);

    // At the start of a command buffer: forgets the previous frame's stages.
    void reset(VkCommandBuffer cb);
    void begin(VkCommandBuffer cb, const std::string& stage);
    void end(VkCommandBuffer cb);
    // After the command buffer completed: one entry per begin/end pair, in order.
    std::vector<GpuStageTime> read() const;

private:
    const VulkanDevice& device_;
    UniqueQueryPool pool_;
    std::uint32_t capacity_;
    std::vector<std::string> names_;
};

}  // namespace hybridlab
