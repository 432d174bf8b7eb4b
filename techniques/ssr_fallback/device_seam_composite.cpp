#include "techniques/ssr_fallback/device_seam_composite.h"

#include "techniques/ssr_fallback/shaders/ssr_records.h"

namespace hybridlab {

using ssr_records::CompositeUniforms;

DeviceSeamComposite::DeviceSeamComposite(const VulkanDevice& device) : device_(device) {
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    descriptors_ = DescriptorSet(device, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, cs, nullptr},
                                          {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr},
                                          {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr},
                                          {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr}});
    layout_ = createPipelineLayout(device, {descriptors_.layout()}, 0);
    pipeline_ = createComputePipeline(device, "ssr_composite.comp", layout_);
    uniforms_ = GpuBuffer(device, sizeof(CompositeUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Memory::DeviceLocalHostVisible);
    counter_ = GpuBuffer(device, sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         GpuBuffer::Memory::HostVisible);
    descriptors_.writeBuffer(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms_.buffer());
    descriptors_.writeBuffer(3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, counter_.buffer());
}

void DeviceSeamComposite::record(VkCommandBuffer cb, const GpuBuffer& texels, const GpuBuffer& image, int width, int height, int radius,
                                 float rangeSigma, bool walewskiBlend) {
    const CompositeUniforms u{{width, height, radius, 0}, {rangeSigma, walewskiBlend ? 1.0f : 0.0f, 0.0f, 0.0f}};
    uniforms_.write(&u, sizeof u);
    descriptors_.writeBuffer(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, texels.buffer());
    descriptors_.writeBuffer(2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, image.buffer());
    recordZeroFillForCompute(cb, counter_.buffer());
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    VkDescriptorSet set = descriptors_.set();
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set, 0, nullptr);
    vkCmdDispatch(cb, static_cast<std::uint32_t>(width + 7) / 8, static_cast<std::uint32_t>(height + 7) / 8, 1);
}

}  // namespace hybridlab
