#include "common/raster/deferred_lighting.h"

#include <cmath>
#include <cstring>

#include <glm/trigonometric.hpp>

#include "common/raster/light_record.h"
#include "common/raster/readback.h"
#include "common/raster/shaders/raster_records.h"
#include "common/raster/vulkan_error.h"
#include "common/raytrace/shading.h"

namespace hybridlab {

namespace {

constexpr VkFormat kOutputFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

using raster_records::FrameUniforms;
using raster_records::LightData;

}  // namespace

DeferredLighting::DeferredLighting(const GpuScene& scene, const GBufferPass& gbuffer, const ShadowMaps& shadows)
    : scene_(scene), gbuffer_(gbuffer), shadows_(shadows) {
    const VulkanDevice& device = scene.device();
    device.requireFormat(kOutputFormat, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT, "the lighting pass's output (P-buffer)");
    const VkShaderStageFlags fs = VK_SHADER_STAGE_FRAGMENT_BIT;
    std::vector<VkDescriptorSetLayoutBinding> bindings = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, fs, nullptr},
                                                          {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, fs, nullptr},
                                                          {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, fs, nullptr},
                                                          {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fs, nullptr},
                                                          {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fs, nullptr}};
    for (std::uint32_t i = 0; i < GBufferPass::kColorTargets; ++i) bindings.push_back({5 + i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fs, nullptr});
    descriptors_ = DescriptorSet(device, bindings);
    layout_ = createPipelineLayout(device, {descriptors_.layout()}, 0);

    nearest_ = createNearestSampler(device, "the G-buffer sampler");

    uniforms_ = GpuBuffer(device, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Memory::DeviceLocalHostVisible);
    const auto& lights = scene.scene().lights;
    std::vector<LightData> data;
    for (std::size_t i = 0; i < lights.size(); ++i) data.push_back(lightRecord(lights[i], shadows.firstLayer(i), shadows.layerCount(i)));
    if (data.empty()) data.emplace_back();  // the array has at least one element
    lights_ = GpuBuffer::withData(device, data.data(), data.size() * sizeof(LightData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
}

void DeferredLighting::resize(std::uint32_t width, std::uint32_t height) {
    if (output_.valid() && output_.desc().width == width && output_.desc().height == height) return;
    const VulkanDevice& device = scene_.device();
    output_ = GpuImage(device, {kOutputFormat, width, height, 1, 1,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
    readback_ = GpuBuffer(device, static_cast<VkDeviceSize>(width) * height * sizeof(glm::vec4), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          GpuBuffer::Memory::HostVisible);
}

void DeferredLighting::record(VkCommandBuffer cb, const Camera& camera, const LightingOptions& options, const ShadowSettings& shadowSettings) {
    const std::uint32_t width = gbuffer_.width(), height = gbuffer_.height();
    resize(width, height);
    const Scene& scene = scene_.scene();
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    FrameUniforms u{};
    const bool perspective = camera.projection == Camera::Projection::Perspective;
    const float halfHeight = perspective ? std::tan(glm::radians(camera.fovYDegrees) * 0.5f) : 0.5f * camera.orthoHeight;
    u.cameraPosition = glm::vec4(camera.position, perspective ? 1.0f : 0.0f);
    u.cameraRight = glm::vec4(camera.right() * (halfHeight * aspect), 0.0f);
    u.cameraUp = glm::vec4(camera.up() * halfHeight, 0.0f);
    u.cameraForward = glm::vec4(camera.forward(), 0.0f);
    u.sceneAmbient = glm::vec4(scene.ambient, scene.ambientIor);
    u.skyColor = glm::vec4(scene.sky.color, 0.0f);
    u.counts = glm::uvec4(static_cast<std::uint32_t>(scene.lights.size()), 0u, width, height);
    u.shadowParams = glm::vec4(static_cast<float>(shadowSettings.pcfRadius), shadowSettings.normalOffsetTexels, 0.0f, 0.0f);
    uniforms_.write(&u, sizeof u);

    // Rewritten every frame: the G-buffer and shadow images are recreated when their sizes change
    // (the previous frame has completed, so the set is not in use).
    descriptors_.writeBuffer(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms_.buffer());
    descriptors_.writeBuffer(1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, lights_.buffer());
    descriptors_.writeBuffer(2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, shadows_.layerBuffer());
    descriptors_.writeImages(3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, {shadows_.depthArray()});
    descriptors_.writeImages(4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, {scene_.textures().sky()});
    for (int i = 0; i < GBufferPass::kColorTargets; ++i)
        descriptors_.writeImage(5 + i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, gbuffer_.targetView(i), nearest_, VK_IMAGE_LAYOUT_GENERAL);

    transitionImage(cb, output_.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = output_.view();
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // every pixel is written
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {width, height}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = 1;
    ri.pColorAttachments = &color;
    vkCmdBeginRendering(cb, &ri);
    const std::array<std::uint32_t, 4> variant = {options.shadows, options.environmentMapping, options.walewskiBlend,
                                                  scene.sky.hasCubeMap()};
    const std::size_t key = variant[0] | variant[1] << 1 | variant[2] << 2 | variant[3] << 3;
    if (!pipelines_[key]) {
        GraphicsPipelineDesc d;
        d.vertexShader = "fullscreen.vert";
        d.fragmentShader = "deferred_lighting.frag";
        d.fragmentConstants.assign(variant.begin(), variant.end());
        d.fragmentConstants.push_back(static_cast<std::uint32_t>(std::max<std::size_t>(1, scene.lights.size())));
        d.fragmentConstants.push_back(static_cast<std::uint32_t>(std::max<std::size_t>(1, shadows_.layers())));
        d.colorFormats = {kOutputFormat};
        d.layout = layout_;
        pipelines_[key] = createGraphicsPipeline(scene_.device(), d);
    }
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_[key]);
    setViewport(cb, width, height);
    VkDescriptorSet set = descriptors_.set();
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set, 0, nullptr);
    vkCmdDraw(cb, 3, 1, 0, 0);
    vkCmdEndRendering(cb);
    transitionImage(cb, output_.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                    VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

void DeferredLighting::recordReadback(VkCommandBuffer cb) {
    recordCopyToBuffer(cb, output_, VK_IMAGE_ASPECT_COLOR_BIT, readback_);
    recordHostReadBarrier(cb);
}

void DeferredLighting::unpack(Image& out) const {
    const int w = static_cast<int>(output_.desc().width), h = static_cast<int>(output_.desc().height);
    if (out.width() != w || out.height() != h) out = Image(w, h);
    std::memcpy(out.data(), readback_.readBack(out.pixelCount() * sizeof(glm::vec4)), out.pixelCount() * sizeof(glm::vec4));
}

}  // namespace hybridlab
