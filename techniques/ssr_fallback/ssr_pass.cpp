#include "techniques/ssr_fallback/ssr_pass.h"

#include <cstring>

#include "common/raster/readback.h"
#include "common/raster/vulkan_error.h"

namespace hybridlab {

namespace {

constexpr VkFormat kOutputFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kPyramidFormat = VK_FORMAT_R32_SFLOAT;
using ssr_records::MarchListHeader;
using ssr_records::PyramidUniforms;
using ssr_records::SsrUniforms;

// Work groups of ssr_depth_pyramid.comp along a side of n cells (ssr_trace.comp's are dispatched indirectly).
std::uint32_t groups(std::uint32_t n) { return (n + ssr_records::kSsrPyramidGroupSize - 1) / ssr_records::kSsrPyramidGroupSize; }

// Compute-shader writes visible to the compute shaders that follow.
void computeToComputeBarrier(VkCommandBuffer cb) {
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &b, 0, nullptr, 0, nullptr);
}

}  // namespace

SsrPass::SsrPass(std::shared_ptr<VulkanDevice> onDevice) : device_(std::move(onDevice)) {
    const VulkanDevice& device = *device_;
    device.requireFormat(kOutputFormat, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT, "the SSR pass's outputs");
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    descriptors_ = DescriptorSet(device, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, cs, nullptr},
                                          {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr},
                                          {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr},
                                          {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr},
                                          {6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr},
                                          {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr},
                                          {8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr},
                                          {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr}});
    layout_ = createPipelineLayout(device, {descriptors_.layout()}, 0);
    for (std::uint32_t hiz = 0; hiz < 2; ++hiz) pipelines_[hiz] = createComputePipeline(device, "ssr_trace.comp", layout_, {hiz});
    device.requireFormat(kPyramidFormat, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT, "the SSR depth pyramid");
    pyramidUniforms_ = GpuBuffer(device, sizeof(PyramidUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Memory::DeviceLocalHostVisible);
    nearest_ = createNearestSampler(device, "the SSR sampler");
    uniforms_ = GpuBuffer(device, sizeof(SsrUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Memory::DeviceLocalHostVisible);
}

void SsrPass::resize(std::uint32_t width, std::uint32_t height) {
    if (color_.valid() && color_.desc().width == width && color_.desc().height == height) return;
    const VulkanDevice& device = *device_;
    // Sampled too: with rays = "vulkan" the ray-traced stage reads them where they lie.
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    color_ = GpuImage(device, {kOutputFormat, width, height, 1, 1, usage});
    hit_ = GpuImage(device, {kOutputFormat, width, height, 1, 1, usage});
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(width) * height * sizeof(glm::vec4);
    colorReadback_ = GpuBuffer(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuBuffer::Memory::HostVisible);
    marchList_ = GpuBuffer(device, sizeof(MarchListHeader) + static_cast<VkDeviceSize>(width) * height * sizeof(std::uint32_t),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                           GpuBuffer::Memory::DeviceLocal);
    // The pyramid: levels down to 1 x 1, each half the one below (rounded down).
    std::uint32_t levels = 1;
    while ((std::max(width, height) >> levels) > 0) ++levels;
    pyramid_ = GpuImage(device, {kPyramidFormat, width, height, levels, 1, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    pyramidLevels_.clear();
    for (std::uint32_t l = 0; l < levels; ++l) pyramidLevels_.push_back(pyramid_.layerView(0, l));
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    pyramidDescriptors_ = DescriptorSet(device, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, cs, nullptr},
                                                 {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr},
                                                 {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr},
                                                 {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr},
                                                 {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, cs, nullptr},
                                                 {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, cs, nullptr},
                                                 {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, cs, nullptr}},
                                        levels);
    if (!pyramidLayout_) {
        pyramidLayout_ = createPipelineLayout(device, {pyramidDescriptors_.layout()}, 0);
        for (std::uint32_t fromGBuffer = 0; fromGBuffer < 2; ++fromGBuffer)
            pyramidPipelines_[fromGBuffer] = createComputePipeline(device, "ssr_depth_pyramid.comp", pyramidLayout_, {fromGBuffer});
    }
    hitReadback_ = GpuBuffer(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuBuffer::Memory::HostVisible);
}

void SsrPass::recordDepthPyramid(VkCommandBuffer cb, const FrameTargets& t) {
    const PyramidUniforms uniforms{t.view, glm::vec4(settings_.refractive ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f)};
    pyramidUniforms_.write(&uniforms, sizeof uniforms);
    // The linear march reads level 0 only.
    const auto levels = settings_.traversal == SsrSettings::Traversal::HiZ ? static_cast<std::uint32_t>(pyramidLevels_.size()) : 1u;
    for (std::uint32_t l = 0; l < levels; ++l) {
        pyramidDescriptors_.writeBuffer(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, pyramidUniforms_.buffer(), l);
        pyramidDescriptors_.writeImage(1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, t.gbuffer[0], nearest_, VK_IMAGE_LAYOUT_GENERAL, l);
        pyramidDescriptors_.writeImage(2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, t.gbuffer[7], nearest_, VK_IMAGE_LAYOUT_GENERAL, l);
        pyramidDescriptors_.writeImage(3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pyramidLevels_[l > 0 ? l - 1 : 0], VK_NULL_HANDLE,
                                       VK_IMAGE_LAYOUT_GENERAL, l);
        pyramidDescriptors_.writeImage(4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, pyramidLevels_[l], VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL, l);
        pyramidDescriptors_.writeImage(5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, t.gbuffer[6], nearest_, VK_IMAGE_LAYOUT_GENERAL, l);
        pyramidDescriptors_.writeBuffer(6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, marchList_.buffer(), l);
    }
    for (std::uint32_t l = 0; l < levels; ++l) {
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pyramidPipelines_[l == 0 ? 1 : 0]);
        VkDescriptorSet set = pyramidDescriptors_.set(l);
        vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pyramidLayout_, 0, 1, &set, 0, nullptr);
        vkCmdDispatch(cb, groups(std::max(1u, t.width >> l)), groups(std::max(1u, t.height >> l)), 1);
        computeToComputeBarrier(cb);
    }
}

void SsrPass::record(VkCommandBuffer cb, const FrameTargets& t) {
    if (t.lighting == VK_NULL_HANDLE) throw VulkanError("the SSR pass needs the lit image: ask the rasterizer for lighting");
    resize(t.width, t.height);
    const Camera& camera = t.camera;
    SsrUniforms u{};
    u.view = t.view;
    u.projection = t.projection;
    u.cameraPosition = glm::vec4(camera.position, camera.projection == Camera::Projection::Perspective ? 1.0f : 0.0f);
    u.cameraForward = glm::vec4(camera.forward(), 0.0f);
    u.march = glm::vec4(static_cast<float>(settings_.maxSteps), static_cast<float>(settings_.stride), settings_.thickness,
                        settings_.maxDistance);
    u.screen = glm::vec4(static_cast<float>(t.width), static_cast<float>(t.height), settings_.edgeFade, camera.nearPlane);
    u.hiz = glm::vec4(static_cast<float>(pyramidLevels_.size() - 1), 0.0f, 0.0f, 0.0f);
    uniforms_.write(&u, sizeof u);

    // Rewritten every frame: the targets are recreated when the frame size changes.
    descriptors_.writeBuffer(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms_.buffer());
    descriptors_.writeImage(1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, t.gbuffer[0], nearest_, VK_IMAGE_LAYOUT_GENERAL);  // position
    descriptors_.writeImage(2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, t.gbuffer[1], nearest_, VK_IMAGE_LAYOUT_GENERAL);  // normal
    descriptors_.writeImage(5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, t.lighting, nearest_, VK_IMAGE_LAYOUT_GENERAL);
    descriptors_.writeImage(6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, color_.view(), VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
    descriptors_.writeImage(7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hit_.view(), VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL);
    descriptors_.writeImage(8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, pyramid_.view(), nearest_, VK_IMAGE_LAYOUT_GENERAL);
    descriptors_.writeBuffer(9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, marchList_.buffer());

    for (const GpuImage* image : {&color_, &hit_})
        transitionImage(cb, image->image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    transitionImage(cb, pyramid_.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                    VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    // The texels the march skips read as not traced: colour 0, no hit, no flags.
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    const VkClearColorValue noColor{{0.0f, 0.0f, 0.0f, 0.0f}}, noHit{{-1.0f, -1.0f, 0.0f, 0.0f}};
    vkCmdClearColorImage(cb, color_.image(), VK_IMAGE_LAYOUT_GENERAL, &noColor, 1, &all);
    vkCmdClearColorImage(cb, hit_.image(), VK_IMAGE_LAYOUT_GENERAL, &noHit, 1, &all);
    const MarchListHeader empty{{0, 1, 1}, 0};
    vkCmdUpdateBuffer(cb, marchList_.buffer(), 0, sizeof empty, &empty);
    VkMemoryBarrier cleared{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &cleared, 0, nullptr, 0, nullptr);

    const bool hiz = settings_.traversal == SsrSettings::Traversal::HiZ;
    recordDepthPyramid(cb, t);  // also lists the texels to march
    VkMemoryBarrier listed{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_INDIRECT_COMMAND_READ_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, 0, 1, &listed, 0, nullptr, 0, nullptr);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_[hiz ? 1 : 0]);
    VkDescriptorSet set = descriptors_.set();
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set, 0, nullptr);
    vkCmdDispatchIndirect(cb, marchList_.buffer(), 0);
    if (readback_) recordReadback(cb);
}

void SsrPass::recordReadback(VkCommandBuffer cb) {
    for (const GpuImage* image : {&color_, &hit_})
        transitionImage(cb, image->image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                        VK_ACCESS_TRANSFER_READ_BIT);
    recordCopyToBuffer(cb, color_, VK_IMAGE_ASPECT_COLOR_BIT, colorReadback_);
    recordCopyToBuffer(cb, hit_, VK_IMAGE_ASPECT_COLOR_BIT, hitReadback_);
    recordHostReadBarrier(cb);
}

void SsrPass::finish() {
    if (readback_) unpack();  // else the caller does, where it recorded the copies
}

void SsrPass::unpack() {
    result_.width = static_cast<int>(color_.desc().width);
    result_.height = static_cast<int>(color_.desc().height);
    const std::size_t n = static_cast<std::size_t>(result_.width) * result_.height;
    result_.pixels.resize(n);
    const auto* color = colorReadback_.readBack<glm::vec4>(n);
    const auto* hit = hitReadback_.readBack<glm::vec4>(n);
    for (std::size_t i = 0; i < n; ++i) {
        SsrPixel& p = result_.pixels[i];
        p.color = glm::vec3(color[i]);
        p.confidence = color[i].w;
        p.hit = glm::ivec2(static_cast<int>(hit[i].x), static_cast<int>(hit[i].y));
        p.flags = static_cast<std::uint32_t>(hit[i].z);
        p.steps = static_cast<int>(hit[i].w);
        if (!p.resolved()) p.hit = glm::ivec2(-1);
    }
}

}  // namespace hybridlab
