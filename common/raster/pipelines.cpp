#include "common/raster/pipelines.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <vector>

#include "common/core/input_error.h"
#include "common/raster/embedded_shaders.h"
#include "common/raster/vulkan_error.h"

namespace hybridlab {

namespace {

// HYBRIDLAB_SHADER_DIR=<dir>: <dir>/<name>.spv, where present, replaces the embedded SPIR-V of
// <name>. For trying a changed shader, or bisecting one on a driver, without rebuilding.
std::vector<std::uint32_t> shaderOverride(const std::string& name) {
    const char* dir = std::getenv("HYBRIDLAB_SHADER_DIR");
    if (!dir || !*dir) return {};
    const std::filesystem::path path = std::filesystem::path(dir) / (name + ".spv");
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return {};
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.is_open() || bytes.empty() || bytes.size() % 4 != 0)
        throw InputError(path.string() + ": expected SPIR-V (a non-empty file of 32-bit words), read " + std::to_string(bytes.size()) +
                         " bytes");
    std::vector<std::uint32_t> words(bytes.size() / 4);
    std::memcpy(words.data(), bytes.data(), bytes.size());
    return words;
}

}  // namespace

UniqueShaderModule createShaderModule(const VulkanDevice& device, const std::string& embeddedName) {
    const std::vector<std::uint32_t> replaced = shaderOverride(embeddedName);
    std::span<const std::uint32_t> code = replaced.empty() ? embeddedShader(embeddedName) : std::span<const std::uint32_t>(replaced);
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = code.size_bytes();
    ci.pCode = code.data();
    VkShaderModule m;
    checkVk(vkCreateShaderModule(device.device(), &ci, nullptr, &m), ("creating shader module " + embeddedName).c_str());
    return UniqueShaderModule(device.device(), m);
}

DescriptorSet::DescriptorSet(const VulkanDevice& device, const std::vector<VkDescriptorSetLayoutBinding>& bindings, std::uint32_t count)
    : device_(device.device()) {
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = static_cast<std::uint32_t>(bindings.size());
    lci.pBindings = bindings.data();
    VkDescriptorSetLayout layout;
    checkVk(vkCreateDescriptorSetLayout(device_, &lci, nullptr, &layout), "creating a descriptor set layout");
    layout_ = UniqueDescriptorSetLayout(device_, layout);

    std::map<VkDescriptorType, std::uint32_t> counts;
    for (const auto& b : bindings) counts[b.descriptorType] += b.descriptorCount;
    std::vector<VkDescriptorPoolSize> sizes;
    for (auto [type, n] : counts) sizes.push_back({type, n * count});
    VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pci.maxSets = count;
    pci.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
    pci.pPoolSizes = sizes.data();
    VkDescriptorPool pool;
    checkVk(vkCreateDescriptorPool(device_, &pci, nullptr, &pool), "creating a descriptor pool");
    pool_ = UniqueDescriptorPool(device_, pool);

    const std::vector<VkDescriptorSetLayout> layouts(count, layout);
    sets_.resize(count);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = count;
    ai.pSetLayouts = layouts.data();
    checkVk(vkAllocateDescriptorSets(device_, &ai, sets_.data()), "allocating descriptor sets");
    VulkanDevice::countAllocations(count);
}

void DescriptorSet::writeBuffer(std::uint32_t binding, VkDescriptorType type, VkBuffer buffer, std::size_t set, VkDeviceSize range) {
    VkDescriptorBufferInfo info{buffer, 0, range};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = sets_[set];
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = type;
    w.pBufferInfo = &info;
    vkUpdateDescriptorSets(device_, 1, &w, 0, nullptr);
}

void DescriptorSet::writeImages(std::uint32_t binding, VkDescriptorType type, const std::vector<VkDescriptorImageInfo>& images,
                                std::size_t set) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = sets_[set];
    w.dstBinding = binding;
    w.descriptorCount = static_cast<std::uint32_t>(images.size());
    w.descriptorType = type;
    w.pImageInfo = images.data();
    vkUpdateDescriptorSets(device_, 1, &w, 0, nullptr);
}

UniquePipelineLayout createPipelineLayout(const VulkanDevice& device, const std::vector<VkDescriptorSetLayout>& sets,
                                          std::uint32_t pushConstantBytes) {
    VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, pushConstantBytes};
    VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    ci.setLayoutCount = static_cast<std::uint32_t>(sets.size());
    ci.pSetLayouts = sets.data();
    ci.pushConstantRangeCount = pushConstantBytes > 0 ? 1 : 0;
    ci.pPushConstantRanges = &range;
    VkPipelineLayout layout;
    checkVk(vkCreatePipelineLayout(device.device(), &ci, nullptr, &layout), "creating a pipeline layout");
    return UniquePipelineLayout(device.device(), layout);
}

UniqueSampler createNearestSampler(const VulkanDevice& device, const char* purpose) {
    VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
    sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VkSampler s;
    checkVk(vkCreateSampler(device.device(), &sci, nullptr, &s), (std::string("creating ") + purpose).c_str());
    return UniqueSampler(device.device(), s);
}

UniquePipeline createComputePipeline(const VulkanDevice& device, const std::string& computeShader, VkPipelineLayout layout,
                                     const std::vector<std::uint32_t>& constants) {
    UniqueShaderModule cs = createShaderModule(device, computeShader);
    std::vector<VkSpecializationMapEntry> entries;
    for (std::uint32_t i = 0; i < constants.size(); ++i) entries.push_back({i, 4 * i, 4});
    const VkSpecializationInfo spec{static_cast<std::uint32_t>(entries.size()), entries.data(), 4 * entries.size(), constants.data()};
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = cs;
    ci.stage.pName = "main";
    ci.stage.pSpecializationInfo = entries.empty() ? nullptr : &spec;
    ci.layout = layout;
    VkPipeline pipeline;
    checkVk(vkCreateComputePipelines(device.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline),
            ("creating compute pipeline " + computeShader).c_str());
    return UniquePipeline(device.device(), pipeline);
}

UniquePipeline createGraphicsPipeline(const VulkanDevice& device, const GraphicsPipelineDesc& desc) {
    UniqueShaderModule vs = createShaderModule(device, desc.vertexShader);
    UniqueShaderModule fs;
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    s.stage = VK_SHADER_STAGE_VERTEX_BIT;
    s.module = vs;
    s.pName = "main";
    stages.push_back(s);
    std::vector<VkSpecializationMapEntry> entries;
    for (std::uint32_t i = 0; i < desc.fragmentConstants.size(); ++i) entries.push_back({i, 4 * i, 4});
    const VkSpecializationInfo spec{static_cast<std::uint32_t>(entries.size()), entries.data(), 4 * entries.size(), desc.fragmentConstants.data()};
    if (!desc.fragmentShader.empty()) {
        fs = createShaderModule(device, desc.fragmentShader);
        s.stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        s.module = fs;
        s.pSpecializationInfo = entries.empty() ? nullptr : &spec;
        stages.push_back(s);
    }

    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = static_cast<std::uint32_t>(desc.vertexBindings.size());
    vi.pVertexBindingDescriptions = desc.vertexBindings.data();
    vi.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(desc.vertexAttributes.size());
    vi.pVertexAttributeDescriptions = desc.vertexAttributes.data();
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = 1;
    vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.depthBiasEnable = desc.dynamicDepthBias ? VK_TRUE : VK_FALSE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = desc.depthTest ? VK_TRUE : VK_FALSE;
    ds.depthWriteEnable = desc.depthWrite ? VK_TRUE : VK_FALSE;
    ds.depthCompareOp = desc.depthCompare;
    if (desc.stencilPassOnce) {
        ds.stencilTestEnable = VK_TRUE;
        ds.front = {VK_STENCIL_OP_KEEP, VK_STENCIL_OP_INCREMENT_AND_CLAMP, VK_STENCIL_OP_KEEP, VK_COMPARE_OP_EQUAL, 0xFF, 0xFF, 0};
        ds.back = ds.front;
    }
    std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
    for (auto& b : blends) b.colorWriteMask = 0xF;
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = static_cast<std::uint32_t>(blends.size());
    cb.pAttachments = blends.data();
    std::vector<VkDynamicState> dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    if (desc.dynamicDepthBias) dynamic.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
    VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dyn.dynamicStateCount = static_cast<std::uint32_t>(dynamic.size());
    dyn.pDynamicStates = dynamic.data();

    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<std::uint32_t>(desc.colorFormats.size());
    rendering.pColorAttachmentFormats = desc.colorFormats.data();
    rendering.depthAttachmentFormat = desc.depthFormat;
    rendering.stencilAttachmentFormat = desc.stencilFormat;

    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    ci.stageCount = static_cast<std::uint32_t>(stages.size());
    ci.pStages = stages.data();
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &ds;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &dyn;
    ci.layout = desc.layout;
    VkPipeline p;
    checkVk(vkCreateGraphicsPipelines(device.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &p),
            ("creating the pipeline of " + desc.vertexShader + (desc.fragmentShader.empty() ? "" : " + " + desc.fragmentShader)).c_str());
    return UniquePipeline(device.device(), p);
}

void recordZeroFillForCompute(VkCommandBuffer cb, VkBuffer buffer) {
    vkCmdFillBuffer(cb, buffer, 0, VK_WHOLE_SIZE, 0);
    VkMemoryBarrier cleared{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &cleared, 0, nullptr, 0, nullptr);
}

void setViewport(VkCommandBuffer cb, std::uint32_t width, std::uint32_t height) {
    VkViewport v{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f};
    VkRect2D s{{0, 0}, {width, height}};
    vkCmdSetViewport(cb, 0, 1, &v);
    vkCmdSetScissor(cb, 0, 1, &s);
}

}  // namespace hybridlab
