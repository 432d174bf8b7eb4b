#include "common/raster/gpu_timer.h"

#include "common/raster/vulkan_error.h"

namespace hybridlab {

GpuTimer::GpuTimer(const VulkanDevice& device, std::uint32_t maxStages) : device_(device), capacity_(maxStages) {
    VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    ci.queryCount = 2 * maxStages;
    VkQueryPool pool;
    checkVk(vkCreateQueryPool(device.device(), &ci, nullptr, &pool), "creating a timestamp query pool");
    pool_ = UniqueQueryPool(device.device(), pool);
}

void GpuTimer::reset(VkCommandBuffer cb) {
    vkCmdResetQueryPool(cb, pool_, 0, 2 * capacity_);
    names_.clear();
}

void GpuTimer::begin(VkCommandBuffer cb, const std::string& stage) {
    if (names_.size() >= capacity_) throw VulkanError("GpuTimer: more than " + std::to_string(capacity_) + " stages in one frame");
    vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 2 * static_cast<std::uint32_t>(names_.size()));
    names_.push_back(stage);
}

void GpuTimer::end(VkCommandBuffer cb) {
    vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 2 * static_cast<std::uint32_t>(names_.size()) - 1);
}

std::vector<GpuStageTime> GpuTimer::read() const {
    std::vector<GpuStageTime> out;
    if (names_.empty()) return out;
    std::vector<std::uint64_t> ticks(2 * names_.size());
    checkVk(vkGetQueryPoolResults(device_.device(), pool_, 0, static_cast<std::uint32_t>(ticks.size()), ticks.size() * sizeof(std::uint64_t),
                                  ticks.data(), sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "reading GPU timestamps");
    for (std::size_t i = 0; i < names_.size(); ++i) {
        const double ns = static_cast<double>(ticks[2 * i + 1] - ticks[2 * i]) * device_.timestampPeriod();
        out.push_back({names_[i], ns * 1e-6});
    }
    return out;
}

}  // namespace hybridlab
