#pragma once
// Shader modules, descriptor sets and graphics pipelines: the boilerplate every pass shares.
// Pipelines render with dynamic rendering (Vulkan 1.3): no render-pass or framebuffer objects.
#include <string>
#include <vector>

#include "common/raster/vk_unique.h"
#include "common/raster/vulkan_device.h"

namespace hybridlab {

UniqueShaderModule createShaderModule(const VulkanDevice& device, const std::string& embeddedName);

// `count` descriptor sets of one layout, with their own pool.
class DescriptorSet {
public:
    DescriptorSet() = default;
    DescriptorSet(const VulkanDevice& device, const std::vector<VkDescriptorSetLayoutBinding>& bindings, std::uint32_t count = 1);

    VkDescriptorSetLayout layout() const { return layout_; }
    VkDescriptorSet set(std::size_t i = 0) const { return sets_[i]; }

    void writeBuffer(std::uint32_t binding, VkDescriptorType type, VkBuffer buffer, std::size_t set = 0, VkDeviceSize range = VK_WHOLE_SIZE);
    void writeImages(std::uint32_t binding, VkDescriptorType type, const std::vector<VkDescriptorImageInfo>& images, std::size_t set = 0);
    void writeImage(std::uint32_t binding, VkDescriptorType type, VkImageView view, VkSampler sampler, VkImageLayout layout,
                    std::size_t set = 0) {
        writeImages(binding, type, {{sampler, view, layout}}, set);
    }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    UniqueDescriptorSetLayout layout_;
    UniqueDescriptorPool pool_;
    std::vector<VkDescriptorSet> sets_;  // freed with the pool
};

UniquePipelineLayout createPipelineLayout(const VulkanDevice& device, const std::vector<VkDescriptorSetLayout>& sets,
                                          std::uint32_t pushConstantBytes);

struct GraphicsPipelineDesc {
    std::string vertexShader;
    std::string fragmentShader;  // empty: depth only
    // Specialization constants of the fragment stage: constant_id i gets value i (bools as 0 or 1).
    // Lavapipe runs both sides of every branch, so features a pass does not use are compiled out.
    std::vector<std::uint32_t> fragmentConstants;
    std::vector<VkVertexInputBindingDescription> vertexBindings;
    std::vector<VkVertexInputAttributeDescription> vertexAttributes;
    std::vector<VkFormat> colorFormats;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    VkFormat stencilFormat = VK_FORMAT_UNDEFINED;
    // Stencil test "equal 0, then increment": each pixel passes once, however many fragments reach it.
    bool stencilPassOnce = false;
    bool depthTest = false;
    bool depthWrite = false;
    VkCompareOp depthCompare = VK_COMPARE_OP_GREATER;  // reverse-Z: nearer is greater
    bool dynamicDepthBias = false;
    VkPipelineLayout layout = VK_NULL_HANDLE;
};

// Viewport and scissor are dynamic state; culling is off (single-sided planes are seen from both
// sides, as by the ray tracer); counter-clockwise triangles are front faces.
UniquePipeline createGraphicsPipeline(const VulkanDevice& device, const GraphicsPipelineDesc& desc);

// A sampler with nearest filtering and clamp-to-edge addressing (texelFetch-like reads of targets).
UniqueSampler createNearestSampler(const VulkanDevice& device, const char* purpose);

// A compute pipeline of shaders/<computeShader> with push constants (if any) for the compute stage
// only; `constants` are its specialization constants (constant_id i gets value i).
UniquePipeline createComputePipeline(const VulkanDevice& device, const std::string& computeShader, VkPipelineLayout layout,
                                     const std::vector<std::uint32_t>& constants = {});

// Records a fill of `buffer` with zeros, and the barrier that makes it visible to compute shaders
// that read and write it (counters cleared each frame).
void recordZeroFillForCompute(VkCommandBuffer cb, VkBuffer buffer);

// Sets the viewport and scissor to the whole of a width x height target.
void setViewport(VkCommandBuffer cb, std::uint32_t width, std::uint32_t height);

}  // namespace hybridlab
