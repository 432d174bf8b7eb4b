#include "common/raster/gpu_timer.h"

#include "common/raster/vulkan_error.h"

namespace hybridlab {

namespace {

// Written in the order of their bits: input primitives, clipping primitives, fragment and compute invocations.
constexpr VkQueryPipelineStatisticFlags kCounted =
    VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT | VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT |
    VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT | VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT;

}  // namespace

GpuTimer::GpuTimer(const VulkanDevice& device, std::uint32_t maxStages, bool statistics) : device_(device), capacity_(maxStages) {
    VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    ci.queryCount = 2 * maxStages;
    VkQueryPool pool;
    checkVk(vkCreateQueryPool(device.device(), &ci, nullptr, &pool), "creating a timestamp query pool");
    pool_ = UniqueQueryPool(device.device(), pool);
    if (statistics && device.pipelineStatistics()) {
        VkQueryPoolCreateInfo si{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        si.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
        si.queryCount = maxStages;
        si.pipelineStatistics = kCounted;
        checkVk(vkCreateQueryPool(device.device(), &si, nullptr, &pool), "creating a pipeline-statistics query pool");
        statistics_ = UniqueQueryPool(device.device(), pool);
    }
}

void GpuTimer::reset(VkCommandBuffer cb, bool countWork) {
    vkCmdResetQueryPool(cb, pool_, 0, 2 * capacity_);
    counting_ = statistics_ && countWork;
    if (counting_) vkCmdResetQueryPool(cb, statistics_, 0, capacity_);
    names_.clear();
}

void GpuTimer::begin(VkCommandBuffer cb, const std::string& stage) {
    if (names_.size() >= capacity_) throw VulkanError("GpuTimer: more than " + std::to_string(capacity_) + " stages in one frame");
    vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 2 * static_cast<std::uint32_t>(names_.size()));
    if (counting_) vkCmdBeginQuery(cb, statistics_, static_cast<std::uint32_t>(names_.size()), 0);
    names_.push_back(stage);
}

void GpuTimer::end(VkCommandBuffer cb) {
    if (counting_) vkCmdEndQuery(cb, statistics_, static_cast<std::uint32_t>(names_.size()) - 1);
    vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 2 * static_cast<std::uint32_t>(names_.size()) - 1);
}

std::vector<GpuStageTime> GpuTimer::read() const {
    std::vector<GpuStageTime> out;
    if (names_.empty()) return out;
    std::vector<std::uint64_t> ticks(2 * names_.size());
    checkVk(vkGetQueryPoolResults(device_.device(), pool_, 0, static_cast<std::uint32_t>(ticks.size()), ticks.size() * sizeof(std::uint64_t),
                                  ticks.data(), sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "reading GPU timestamps");
    VulkanDevice::countReadBack(ticks.size() * sizeof(std::uint64_t));
    std::vector<std::uint64_t> counts;
    if (counting_) {
        counts.resize(4 * names_.size());
        checkVk(vkGetQueryPoolResults(device_.device(), statistics_, 0, static_cast<std::uint32_t>(names_.size()),
                                      counts.size() * sizeof(std::uint64_t), counts.data(), 4 * sizeof(std::uint64_t),
                                      VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
                "reading pipeline statistics");
        VulkanDevice::countReadBack(counts.size() * sizeof(std::uint64_t));
    }
    for (std::size_t i = 0; i < names_.size(); ++i) {
        const double ns = static_cast<double>(ticks[2 * i + 1] - ticks[2 * i]) * device_.timestampPeriod();
        out.push_back({names_[i], ns * 1e-6, std::nullopt});
        if (counting_) out.back().statistics = PipelineStatistics{counts[4 * i], counts[4 * i + 1], counts[4 * i + 2], counts[4 * i + 3]};
    }
    return out;
}

}  // namespace hybridlab
