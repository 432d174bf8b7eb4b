#include "techniques/layered_em/layered_em_pass.h"

#include <algorithm>
#include <cstring>

#include <glm/mat4x4.hpp>

#include "common/raster/readback.h"
#include "common/raster/vulkan_error.h"

namespace hybridlab {

namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

using GpuLensVertex = layered_em_records::LensVertex;
using layered_em_records::LensDrawConstants;
static_assert(layered_em_records::kDrawnPathTerms == kPathTerms);

// A mapped buffer of at least `bytes` (grown, never shrunk), in device memory where the device maps
// it (the lens pass reads it every frame); true when it was (re)allocated, its contents lost.
bool ensureBuffer(const VulkanDevice& device, GpuBuffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage) {
    bytes = std::max<VkDeviceSize>(bytes, 16);
    if (buffer.valid() && buffer.size() >= bytes) return false;
    buffer = GpuBuffer(device, bytes + bytes / 2, usage, GpuBuffer::Memory::DeviceLocalHostVisible);
    return true;
}

}  // namespace

LayeredEmPass::LayeredEmPass() : device_(VulkanDevice::shared()) {
    const VulkanDevice& device = *device_;
    device.requireFormat(kColorFormat, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT, "the layered-EM lens image");
    device.requireFormat(kDepthFormat, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT, "the layered-EM lens depth");
    const VkShaderStageFlags vs = VK_SHADER_STAGE_VERTEX_BIT, fs = VK_SHADER_STAGE_FRAGMENT_BIT;
    descriptors_ = DescriptorSet(device, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, vs, nullptr},
                                          {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, fs, nullptr},
                                          {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, fs, nullptr}});
    layout_ = createPipelineLayout(device, {descriptors_.layout()}, sizeof(LensDrawConstants));
    GraphicsPipelineDesc d;
    d.vertexShader = "layered_em.vert";
    d.fragmentShader = "layered_em.frag";
    d.colorFormats = {kColorFormat};
    d.depthFormat = kDepthFormat;
    d.depthTest = true;
    d.depthWrite = true;  // the nearest lens surface, as rasterizeLens keeps
    d.layout = layout_;
    pipeline_ = createGraphicsPipeline(device, d);
    nearest_ = createNearestSampler(device, "the layered-EM G-buffer reads");
}

void LayeredEmPass::resize(std::uint32_t width, std::uint32_t height) {
    if (color_.valid() && color_.desc().width == width && color_.desc().height == height) return;
    const VulkanDevice& device = *device_;
    color_ = GpuImage(device, {kColorFormat, width, height, 1, 1, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
    depth_ = GpuImage(device, {kDepthFormat, width, height, 1, 1, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
    readback_ = GpuBuffer(device, static_cast<VkDeviceSize>(width) * height * sizeof(glm::vec4), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          GpuBuffer::Memory::HostVisible);
}

// The frame's vertices, indices and the cube maps of the blended viewpoint samples, packed. The
// cube maps are copied only when the drawn (EM, sample A, sample B) change: along a path that is
// once a viewpoint interval, and the copy (7 layers x 2 samples, 29 MB at 128 texels a face) is
// otherwise a large part of the frame on a host-memory device.
void LayeredEmPass::upload() {
    std::size_t vertexCount = 0, indexCount = 0, texelCount = 0;
    std::vector<ResidentTexels> resident;
    for (const LensDraw& d : draws_) {
        resident.push_back({d.em, d.blend.a, d.blend.b});
        if (d.em->layers.size() > static_cast<std::size_t>(kMaxDrawnLayers))
            throw VulkanError("the layered-EM pass draws at most " + std::to_string(kMaxDrawnLayers) + " layers");
        vertexCount += d.geometry->positions.size();
        indexCount += 3 * d.geometry->triangles.size();
        for (std::size_t v : {d.blend.a, d.blend.b})
            for (const LayerCubeMap& m : d.em->viewpoints[v].maps) texelCount += m.texels.size();
    }
    const VulkanDevice& device = *device_;
    ensureBuffer(device, vertices_, vertexCount * sizeof(GpuLensVertex), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    ensureBuffer(device, indices_, indexCount * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    const bool reallocated = ensureBuffer(device, texels_, texelCount * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    const bool texelsInPlace = !reallocated && resident == residentTexels_;
    auto* vertexOut = static_cast<GpuLensVertex*>(vertices_.mapped());
    auto* indexOut = static_cast<std::uint32_t*>(indices_.mapped());
    auto* texelOut = static_cast<glm::vec4*>(texels_.mapped());
    ranges_.clear();
    std::size_t vertex = 0, index = 0, texel = 0;
    for (const LensDraw& d : draws_) {
        const LensDrawGeometry& g = *d.geometry;
        Range r;
        r.firstIndex = static_cast<std::uint32_t>(index);
        r.indexCount = static_cast<std::uint32_t>(3 * g.triangles.size());
        r.firstVertex = static_cast<std::int32_t>(vertex);
        for (std::size_t i = 0; i < g.positions.size(); ++i) {
            GpuLensVertex out{};
            out.position = glm::vec4(g.positions[i], 1.0f);
            for (int t = 0; t < kPathTerms; ++t) {
                out.weight[t] = glm::vec4(g.weights[t][i], 0.0f);
                out.sky[t] = glm::vec4(g.skyWeights[t][i], 0.0f);
                for (std::size_t l = 0; l < g.indices[t].size(); ++l)
                    out.direction[static_cast<std::size_t>(t) * kMaxDrawnLayers + l] = glm::vec4(g.indices[t][l].directions[i], g.indices[t][l].lods[i]);
            }
            vertexOut[vertex++] = out;
        }
        for (const glm::uvec3& t : g.triangles)
            for (int k = 0; k < 3; ++k) indexOut[index++] = t[k];
        for (int which = 0; which < 2; ++which) {
            (which == 0 ? r.texelsA : r.texelsB) = static_cast<std::int32_t>(texel);
            for (const LayerCubeMap& m : d.em->viewpoints[which == 0 ? d.blend.a : d.blend.b].maps) {
                if (!texelsInPlace) std::memcpy(texelOut + texel, m.texels.data(), m.texels.size() * sizeof(glm::vec4));
                texel += m.texels.size();
            }
        }
        ranges_.push_back(r);
    }
    residentTexels_ = std::move(resident);
}

void LayeredEmPass::record(VkCommandBuffer cb, const FrameTargets& t) {
    resize(t.width, t.height);
    upload();
    descriptors_.writeBuffer(0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, vertices_.buffer());
    descriptors_.writeBuffer(1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, texels_.buffer());
    descriptors_.writeImage(2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, t.gbuffer[0], nearest_, VK_IMAGE_LAYOUT_GENERAL);

    transitionImage(cb, color_.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                    VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    transitionImage(cb, depth_.image(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    auto attachment = [](VkImageView view, VkImageLayout layout, VkAttachmentStoreOp store) {
        VkRenderingAttachmentInfo a{};
        a.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
        a.imageView = view;
        a.imageLayout = layout;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // colour 0 (alpha 0: no lens); depth 0, reverse-Z's far plane
        a.storeOp = store;
        return a;
    };
    const VkRenderingAttachmentInfo color = attachment(color_.view(), VK_IMAGE_LAYOUT_GENERAL, VK_ATTACHMENT_STORE_OP_STORE);
    const VkRenderingAttachmentInfo depth = attachment(depth_.view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_ATTACHMENT_STORE_OP_DONT_CARE);
    VkRenderingInfo ri{};
    ri.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
    ri.renderArea = {{0, 0}, {t.width, t.height}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = 1;
    ri.pColorAttachments = &color;
    ri.pDepthAttachment = &depth;
    vkCmdBeginRendering(cb, &ri);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    setViewport(cb, t.width, t.height);
    VkDescriptorSet set = descriptors_.set();
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set, 0, nullptr);
    vkCmdBindIndexBuffer(cb, indices_.buffer(), 0, VK_INDEX_TYPE_UINT32);
    for (std::size_t i = 0; i < draws_.size(); ++i) {
        const Range& r = ranges_[i];
        if (r.indexCount == 0) continue;
        const LensDraw& d = draws_[i];
        LensDrawConstants c{};
        c.viewProj = t.projection * t.view;
        c.cameraPosition = glm::vec4(t.camera.position, kOcclusionTolerance);
        const int size = d.em->viewpoints[d.blend.a].maps.empty() ? 1 : d.em->viewpoints[d.blend.a].maps[0].size;
        c.maps = glm::ivec4(static_cast<int>(d.em->layers.size()), size, r.texelsA, r.texelsB);
        c.chain = glm::ivec4(cubeMapLevels(size), static_cast<int>(cubeMapTexelCount(size)), 0, 0);
        c.blend = glm::vec4(d.blend.weightA, d.blend.weightB, 0.0f, 0.0f);
        vkCmdPushConstants(cb, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof c, &c);
        vkCmdDrawIndexed(cb, r.indexCount, 1, r.firstIndex, r.firstVertex, 0);
    }
    vkCmdEndRendering(cb);

    transitionImage(cb, color_.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                    VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_READ_BIT);
    recordCopyToBuffer(cb, color_, VK_IMAGE_ASPECT_COLOR_BIT, readback_);
    recordHostReadBarrier(cb);
}

void LayeredEmPass::finish() {
    const int w = static_cast<int>(color_.desc().width), h = static_cast<int>(color_.desc().height);
    if (result_.width() != w || result_.height() != h) result_ = Image(w, h);
    const std::size_t bytes = static_cast<std::size_t>(w) * h * sizeof(glm::vec4);
    std::memcpy(result_.data(), readback_.readBack(bytes), bytes);
    draws_.clear();
}

}  // namespace hybridlab
