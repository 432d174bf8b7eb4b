#include "common/device_rays/device_gbuffer_tracer.h"

#include <algorithm>
#include <cstring>

#include "common/device_rays/device_whitted_tracer.h"
#include "common/raster/vulkan_error.h"

namespace hybridlab {

using namespace device_rays;

namespace {

constexpr std::uint32_t kTechniqueCounters = 16;

// Set 1 of device_gbuffer_inputs.glsl: the G-buffer's eight targets and the lit image (0-8), the
// per-object data (9), SSR's outputs (10, 11), the per-texel records (12), the technique's counters
// (13), the compacted launch's texel list (14); read by the ray-generation shader and the
// classification pass.
std::vector<VkDescriptorSetLayoutBinding> inputBindings() {
    const VkShaderStageFlags raygen = VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_COMPUTE_BIT;
    std::vector<VkDescriptorSetLayoutBinding> b;
    for (std::uint32_t i = 0; i <= 8; ++i) b.push_back({i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, raygen, nullptr});
    b.push_back({9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, raygen, nullptr});
    b.push_back({10, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, raygen, nullptr});
    b.push_back({11, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, raygen, nullptr});
    b.push_back({12, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, raygen, nullptr});
    b.push_back({13, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, raygen, nullptr});
    b.push_back({14, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, raygen, nullptr});
    return b;
}

}  // namespace

// The texel list of a width x height launch: its header and a texel at most per texel.
GpuBuffer texelList(const VulkanDevice& dev, std::size_t texels) {
    return GpuBuffer(dev, sizeof(TexelListHeader) + texels * sizeof(std::uint32_t),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                         VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                     GpuBuffer::Memory::DeviceLocal);
}

DeviceGBufferTracer::DeviceGBufferTracer(const DeviceRayScene& scene, const std::string& raygenShader, const std::string& classifyShader)
    : scene_(scene), pipeline_(scene, raygenShader, inputBindings()) {
    const VulkanDevice& dev = pipeline_.device();
    nearest_ = createNearestSampler(dev, "the G-buffer tracer's sampler");
    // Counted and listed in device memory, copied to the host at the end of each launch.
    counts_ = GpuBuffer(dev, kTechniqueCounters * sizeof(std::uint32_t),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        GpuBuffer::Memory::DeviceLocal);
    countsOnHost_ = GpuBuffer(dev, counts_.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuBuffer::Memory::HostVisible);
    listHeaderOnHost_ = GpuBuffer(dev, sizeof(TexelListHeader), VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuBuffer::Memory::HostVisible);
    pipeline_.inputs().writeBuffer(13, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, counts_.buffer());
    setObjectData({0u});
    if (!classifyShader.empty() && dev.traceRaysIndirect()) classify_ = createComputePipeline(dev, classifyShader, pipeline_.layout());
    list_ = texelList(dev, 1);
    pipeline_.inputs().writeBuffer(14, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, list_.buffer());
}

void DeviceGBufferTracer::setObjectData(const std::vector<std::uint32_t>& data) {
    const VkDeviceSize bytes = std::max<std::size_t>(1, data.size()) * sizeof(std::uint32_t);
    if (!objectData_.valid() || objectData_.size() != bytes) {
        objectData_ = GpuBuffer(pipeline_.device(), bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Memory::DeviceLocalHostVisible);
        pipeline_.inputs().writeBuffer(9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, objectData_.buffer());
    }
    if (!data.empty()) objectData_.write(data.data(), data.size() * sizeof(std::uint32_t));
}

void DeviceGBufferTracer::record(VkCommandBuffer cb, const FrameTargets& targets, const WhittedSettings& settings, std::uint32_t flags,
                                 const std::function<void(VkCommandBuffer)>& after, const std::string& afterStage) {
    if (targets.lighting == VK_NULL_HANDLE) throw VulkanError("the G-buffer tracer needs the lit image: ask the rasterizer for lighting");
    const VulkanDevice& dev = pipeline_.device();
    const int width = static_cast<int>(targets.width), height = static_cast<int>(targets.height);
    const std::size_t texelCount = static_cast<std::size_t>(width) * height;
    DeviceFrame f = deviceFrame(scene_, targets.camera, width, height, settings);
    f.rules.y = flags;
    const bool compact = compactsLaunches();
    lastCompact_ = compact;
    f.rules.z = compact ? 1u : 0u;
    pipeline_.setFrame(f);
    image_ = &pipeline_.output(texelCount * sizeof(glm::vec4));
    const VkDeviceSize texelBytes = texelCount * kTexelRecords * sizeof(glm::vec4);
    if (!texels_.valid() || texels_.size() != texelBytes) {
        texels_ = GpuBuffer(dev, texelBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, GpuBuffer::Memory::DeviceLocal);
        pipeline_.inputs().writeBuffer(12, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, texels_.buffer());
    }
    // Rewritten every frame: the rasterizer recreates its targets when the frame size changes.
    DescriptorSet& in = pipeline_.inputs();
    const VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    for (int i = 0; i < GBufferPass::kColorTargets; ++i) in.writeImage(i, sampled, targets.gbuffer[i], nearest_, VK_IMAGE_LAYOUT_GENERAL);
    in.writeImage(8, sampled, targets.lighting, nearest_, VK_IMAGE_LAYOUT_GENERAL);
    // Without SSR the bindings still need valid images: the lit image stands in, unread.
    in.writeImage(10, sampled, ssrColor_ ? ssrColor_ : targets.lighting, nearest_, VK_IMAGE_LAYOUT_GENERAL);
    in.writeImage(11, sampled, ssrHit_ ? ssrHit_ : targets.lighting, nearest_, VK_IMAGE_LAYOUT_GENERAL);
    RayLaunch launch{targets.width, targets.height, "trace"};
    launch.before = [&](VkCommandBuffer cb) { vkCmdFillBuffer(cb, counts_.buffer(), 0, VK_WHOLE_SIZE, 0); };
    launch.readBack = [&](VkCommandBuffer cb) {
        const VkBufferCopy counts{0, 0, counts_.size()};
        vkCmdCopyBuffer(cb, counts_.buffer(), countsOnHost_.buffer(), 1, &counts);
        if (compact) {
            const VkBufferCopy header{0, 0, sizeof(TexelListHeader)};
            vkCmdCopyBuffer(cb, list_.buffer(), listHeaderOnHost_.buffer(), 1, &header);
        }
    };
    if (compact) {
        if (list_.size() < sizeof(TexelListHeader) + texelCount * sizeof(std::uint32_t)) {
            list_ = texelList(dev, texelCount);
            in.writeBuffer(14, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, list_.buffer());
        }
        launch.classifyStage = "classify";
        launch.indirect = list_.deviceAddress(dev);
        launch.classify = [&](VkCommandBuffer cb) {
            const TexelListHeader empty{{0u, 1u, 1u, 0u}};
            vkCmdUpdateBuffer(cb, list_.buffer(), 0, sizeof(empty), &empty);
            VkMemoryBarrier cleared{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
            vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &cleared, 0, nullptr, 0, nullptr);
            vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, classify_);
            pipeline_.bindSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE);
            vkCmdDispatch(cb, (targets.width + 7) / 8, (targets.height + 7) / 8, 1);  // texel_list.glsl's 8 x 8 tiles
        };
    }
    launch.after = after;
    launch.afterStage = afterStage;
    pipeline_.record(cb, launch);
}

DeviceGBufferTrace DeviceGBufferTracer::trace(const FrameTargets& targets, const WhittedSettings& settings, std::uint32_t flags,
                                              const std::function<void(VkCommandBuffer)>& after, const std::string& afterStage) {
    pipeline_.device().submitAndWait([&](VkCommandBuffer cb) { record(cb, targets, settings, flags, after, afterStage); });
    return lastTrace();
}

DeviceGBufferTrace DeviceGBufferTracer::lastTrace() const {
    const DeviceLaunchCounts counts = pipeline_.counts();
    DeviceGBufferTrace result;
    result.rays = counts.rays;
    result.invocations = counts.invocations;
    if (lastCompact_) result.invocations.listed = listHeaderOnHost_.readBack<TexelListHeader>(1)->launch.x;
    std::memcpy(result.techniqueCounts.data(), countsOnHost_.readBack(sizeof(result.techniqueCounts)), sizeof(result.techniqueCounts));
    result.gpuStages = pipeline_.gpuStages();
    return result;
}

const glm::vec4* DeviceGBufferTracer::readTexels(const std::function<void(VkCommandBuffer)>& alsoCopy) {
    const VulkanDevice& dev = pipeline_.device();
    if (!texelsOnHost_.valid() || texelsOnHost_.size() != texels_.size())
        texelsOnHost_ = GpuBuffer(dev, texels_.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuBuffer::Memory::HostVisible);
    const VulkanDevice::Diagnostics diagnostics;
    dev.submitAndWait([&](VkCommandBuffer cb) {
        if (alsoCopy) alsoCopy(cb);
        const VkBufferCopy all{0, 0, texels_.size()};
        vkCmdCopyBuffer(cb, texels_.buffer(), texelsOnHost_.buffer(), 1, &all);
        VkMemoryBarrier copied{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &copied, 0, nullptr, 0, nullptr);
    });
    return static_cast<const glm::vec4*>(texelsOnHost_.readBack(texelsOnHost_.size()));
}

}  // namespace hybridlab
