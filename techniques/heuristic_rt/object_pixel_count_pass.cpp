#include "techniques/heuristic_rt/object_pixel_count_pass.h"

namespace hybridlab {

ObjectPixelCountPass::ObjectPixelCountPass(std::shared_ptr<VulkanDevice> device, std::size_t objectCount)
    : device_(std::move(device)), objects_(objectCount) {
    const VulkanDevice& dev = *device_;
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    descriptors_ = DescriptorSet(dev, {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr},
                                       {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr}});
    layout_ = createPipelineLayout(dev, {descriptors_.layout()}, 0);
    pipeline_ = createComputePipeline(dev, "object_pixel_count.comp", layout_);
    nearest_ = createNearestSampler(dev, "the visible-pixel count's sampler");
    // Counted in device memory: on a GPU, every texel's atomic add to host memory would cross PCIe.
    buffer_ = GpuBuffer(dev, (objects_ + 1) * sizeof(std::uint32_t),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                        GpuBuffer::Memory::DeviceLocal);
    onHost_ = GpuBuffer(dev, buffer_.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuBuffer::Memory::HostVisible);
    descriptors_.writeBuffer(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffer_.buffer());
}

void ObjectPixelCountPass::record(VkCommandBuffer cb, const FrameTargets& t) {
    descriptors_.writeImage(0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, t.gbuffer[7], nearest_, VK_IMAGE_LAYOUT_GENERAL);
    recordZeroFillForCompute(cb, buffer_.buffer());
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    VkDescriptorSet set = descriptors_.set();
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set, 0, nullptr);
    vkCmdDispatch(cb, (t.width + 7) / 8, (t.height + 7) / 8, 1);
    VkMemoryBarrier counted{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &counted, 0, nullptr, 0, nullptr);
    const VkBufferCopy copy{0, 0, buffer_.size()};
    vkCmdCopyBuffer(cb, buffer_.buffer(), onHost_.buffer(), 1, &copy);
    VkMemoryBarrier copied{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &copied, 0, nullptr, 0, nullptr);
}

void ObjectPixelCountPass::finish() {
    const auto* c = onHost_.readBack<std::uint32_t>(objects_ + 1);
    counts_.assign(c + 1, c + 1 + objects_);
}

}  // namespace hybridlab
