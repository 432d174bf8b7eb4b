#include "common/raster/gbuffer_pass.h"

#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/raster/frustum.h"
#include "common/raster/half_float.h"
#include "common/raster/readback.h"
#include "common/raster/vulkan_error.h"

namespace hybridlab {

namespace {

// A later pass reads (EQUAL tests) and writes the depth and stencil an earlier pass wrote.
void recordDepthWritesBeforeTests(VkCommandBuffer cb) {
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT, 0, 1, &b, 0, nullptr, 0,
                         nullptr);
}

// Formats of the colour targets, in attachment order (Walewski 2019 Table 2 uses RGBA8 for the
// material colours; half floats keep HDR emission and fine material values).
constexpr std::array<VkFormat, GBufferPass::kColorTargets> kFormats = {
    VK_FORMAT_R32G32B32A32_SFLOAT,  // position
    VK_FORMAT_R16G16B16A16_SFLOAT,  // normal
    VK_FORMAT_R16G16B16A16_SFLOAT,  // emission
    VK_FORMAT_R16G16B16A16_SFLOAT,  // ambient
    VK_FORMAT_R16G16B16A16_SFLOAT,  // diffuse
    VK_FORMAT_R16G16B16A16_SFLOAT,  // specular
    VK_FORMAT_R16G16B16A16_SFLOAT,  // optical
    VK_FORMAT_R32_UINT,             // object id
};
// 32-bit float reverse-Z depth (Walewski 2019 §3.1, Table 2); the stencil serves the visible-pixel
// queries only.
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT_S8_UINT;
constexpr std::array<const char*, GBufferPass::kColorTargets> kNames = {"position", "normal", "emission", "ambient",
                                                                        "diffuse", "specular", "optical", "object id"};

std::size_t texelBytes(VkFormat f) {
    switch (f) {
        case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
        case VK_FORMAT_R16G16B16A16_SFLOAT: return 8;
        default: return 4;
    }
}

// Unpacking is part of every hybrid frame's rasterization stage (six 16-bit targets at 720p are
// 22 M values): a table of all 65536 halves and both cores.
void unpackHalf4(const void* src, std::size_t texels, std::vector<glm::vec4>& out) {
    static const std::vector<float> table = [] {
        std::vector<float> t(65536);
        for (std::uint32_t h = 0; h < 65536; ++h) t[h] = halfToFloat(static_cast<std::uint16_t>(h));
        return t;
    }();
    out.resize(texels);
    const auto* h = static_cast<const std::uint16_t*>(src);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, texels, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i)
            out[i] = {table[h[4 * i]], table[h[4 * i + 1]], table[h[4 * i + 2]], table[h[4 * i + 3]]};
    });
}

// The inverse of unpackHalf4: the host's G-buffer into a 16-bit float target's staging memory.
void packHalf4(const std::vector<glm::vec4>& in, void* dst) {
    auto* h = static_cast<std::uint16_t*>(dst);
    const float* f = &in.data()->x;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.size(), 16384), [&](const tbb::blocked_range<std::size_t>& r) {
        floatsToHalves(f + 4 * r.begin(), h + 4 * r.begin(), 4 * r.size());
    });
}

}  // namespace

GBufferPass::GBufferPass(const GpuScene& scene) : scene_(scene) {
    const VulkanDevice& device = scene.device();
    for (std::size_t i = 0; i < kFormats.size(); ++i) {
        device.requireFormat(kFormats[i], VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT,
                             (std::string("the G-buffer's ") + kNames[i] + " target").c_str());
    }
    device.requireFormat(kDepthFormat, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT, "the G-buffer's reverse-Z depth buffer");
    if (device.features().rayTracing) {
        for (std::size_t i = 0; i < kFormats.size(); ++i)
            device.requireFormat(kFormats[i], VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT,
                                 (std::string("primary rays into the G-buffer's ") + kNames[i] + " target").c_str());
    }
    layout_ = createPipelineLayout(device, {scene.descriptors().layout(), scene.materialTextures().layout()}, sizeof(DrawConstants));
    // One vertex stage for the pre-pass, the G-buffer and the visible-pixel pass: its gl_Position
    // is invariant, so the depths repeat exactly and EQUAL tests are exact.
    GraphicsPipelineDesc d;
    d.vertexShader = "gbuffer.vert";
    d.vertexBindings = GpuScene::vertexBindings();
    d.vertexAttributes = GpuScene::vertexAttributes(false);
    d.depthFormat = kDepthFormat;
    d.stencilFormat = kDepthFormat;
    d.depthTest = true;
    d.layout = layout_;
    d.depthWrite = true;
    d.depthCompare = VK_COMPARE_OP_GREATER;
    prepassPipeline_ = createGraphicsPipeline(device, d);

    // Coincident fragments (Sponza has coincident faces) all pass EQUAL; the stencil lets the first
    // drawn through and no other, in the G-buffer as in the visible-pixel queries, so that both
    // give a pixel to the same object.
    d.depthWrite = false;
    d.depthCompare = VK_COMPARE_OP_EQUAL;
    d.stencilPassOnce = true;
    queryPipeline_ = createGraphicsPipeline(device, d);

    d.fragmentShader = "gbuffer.frag";
    d.colorFormats.assign(kFormats.begin(), kFormats.end());
    for (int v = 0; v < 4; ++v) {
        d.fragmentConstants = {v & 1 ? 1u : 0u, v & 2 ? 1u : 0u};
        pipelines_[v] = createGraphicsPipeline(device, d);
    }
    for (const MeshDraw& draw : scene.draws()) {
        const Material& m = scene.scene().materials[draw.material];
        drawVariant_.push_back((m.diffuseTexture != kNoTexture ? 1 : 0) |
                               (m.normalTexture != kNoTexture && (draw.flags & kHasTangentSpace) ? 2 : 0));
    }
}

void GBufferPass::resize(std::uint32_t width, std::uint32_t height) {
    if (width == width_ && height == height_) return;
    const VulkanDevice& device = scene_.device();
    // Storage only where primary rays may write them: elsewhere it would cost a GPU its compression.
    const VkImageUsageFlags storage = device.features().rayTracing ? VK_IMAGE_USAGE_STORAGE_BIT : 0;
    for (std::size_t i = 0; i < kFormats.size(); ++i) {
        color_[i] = GpuImage(device, {kFormats[i], width, height, 1, 1,
                                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                          VK_IMAGE_USAGE_TRANSFER_DST_BIT | storage});
    }
    depth_ = GpuImage(device, {kDepthFormat, width, height, 1, 1, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
    for (auto& r : readback_) r = GpuBuffer();
    for (auto& u : upload_) u = GpuBuffer();
    width_ = width;
    height_ = height;
}

std::size_t GBufferPass::record(VkCommandBuffer cb, const glm::mat4& viewProj) {
    for (const GpuImage& c : color_) {
        transitionImage(cb, c.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    }
    transitionImage(cb, depth_.image(), depth_.aspect(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);

    const Frustum frustum(viewProj);
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = depth_.view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {0.0f, 0};  // reverse-Z: the far plane; stencil 0
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {width_, height_}};
    ri.layerCount = 1;
    ri.pDepthAttachment = &depth;
    ri.pStencilAttachment = &depth;
    vkCmdBeginRendering(cb, &ri);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, prepassPipeline_);
    setViewport(cb, width_, height_);
    scene_.bind(cb);
    for (std::size_t d = 0; d < scene_.draws().size(); ++d)
        if (frustum.intersects(scene_.worldBounds(d))) scene_.recordDraw(cb, layout_, viewProj, d, false);
    vkCmdEndRendering(cb);
    recordDepthWritesBeforeTests(cb);

    std::array<VkRenderingAttachmentInfo, kColorTargets> colors{};
    for (int i = 0; i < kColorTargets; ++i) {
        colors[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        colors[i].imageView = color_[i].view();
        colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        colors[i].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};  // object id 0: the sky
    }
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    ri.colorAttachmentCount = kColorTargets;
    ri.pColorAttachments = colors.data();
    vkCmdBeginRendering(cb, &ri);
    setViewport(cb, width_, height_);
    // In object order, as the visible-pixel pass.
    std::size_t draws = 0;
    int bound = -1;
    for (std::size_t d = 0; d < scene_.draws().size(); ++d) {
        if (!frustum.intersects(scene_.worldBounds(d))) continue;
        if (drawVariant_[d] != bound) {
            bound = drawVariant_[d];
            vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_[bound]);
        }
        scene_.recordDraw(cb, layout_, viewProj, d, true);
        ++draws;
    }
    vkCmdEndRendering(cb);
    return draws;
}

void GBufferPass::recordVisiblePixelQueries(VkCommandBuffer cb, const glm::mat4& viewProj, VkQueryPool queries) {
    const auto objects = static_cast<std::uint32_t>(scene_.scene().objects.size());
    vkCmdResetQueryPool(cb, queries, 0, objects);
    recordDepthWritesBeforeTests(cb);
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = depth_.view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingAttachmentInfo stencil = depth;  // the G-buffer pass marked its pixels: start from 0 again
    stencil.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    stencil.clearValue.depthStencil = {0.0f, 0};
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {width_, height_}};
    ri.layerCount = 1;
    ri.pDepthAttachment = &depth;
    ri.pStencilAttachment = &stencil;
    vkCmdBeginRendering(cb, &ri);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, queryPipeline_);
    setViewport(cb, width_, height_);
    scene_.bind(cb);
    const Frustum frustum(viewProj);
    for (std::uint32_t o = 0; o < objects; ++o) {
        vkCmdBeginQuery(cb, queries, o, VK_QUERY_CONTROL_PRECISE_BIT);
        const auto [first, last] = scene_.objectDraws(o);
        for (std::size_t d = first; d < last; ++d)
            if (frustum.intersects(scene_.worldBounds(d))) scene_.recordDraw(cb, layout_, viewProj, d, false);
        vkCmdEndQuery(cb, queries, o);
    }
    vkCmdEndRendering(cb);
}

void GBufferPass::recordFinish(VkCommandBuffer cb) {
    for (const GpuImage& c : color_) {
        transitionImage(cb, c.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
    }
    transitionImage(cb, depth_.image(), depth_.aspect(), VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                    VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_READ_BIT);
}

void GBufferPass::recordUpload(VkCommandBuffer cb, const GBuffer& host) {
    if (host.width != static_cast<int>(width_) || host.height != static_cast<int>(height_) ||
        !host.has(kGBufferPosition | kGBufferNormal | kGBufferMaterial | kGBufferObjectId)) {
        throw VulkanError("G-buffer upload: the host G-buffer must be " + std::to_string(width_) + " x " + std::to_string(height_) +
                          " and hold every colour target");
    }
    const VulkanDevice& device = scene_.device();
    const std::size_t n = host.pixelCount();
    const std::array<const std::vector<glm::vec4>*, kColorTargets> vec4Targets = {
        &host.position, &host.normal, &host.emission, &host.ambient, &host.diffuse, &host.specular, &host.optical, nullptr};
    for (int i = 0; i < kColorTargets; ++i) {
        if (!upload_[i].valid())
            upload_[i] = GpuBuffer(device, n * texelBytes(kFormats[i]), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, GpuBuffer::Memory::HostVisible);
        if (kFormats[i] == VK_FORMAT_R32_UINT) std::memcpy(upload_[i].mapped(), host.objectId.data(), n * sizeof(std::uint32_t));
        else if (kFormats[i] == VK_FORMAT_R32G32B32A32_SFLOAT) std::memcpy(upload_[i].mapped(), vec4Targets[i]->data(), n * sizeof(glm::vec4));
        else packHalf4(*vec4Targets[i], upload_[i].mapped());
        transitionImage(cb, color_[i].image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {width_, height_, 1};
        vkCmdCopyBufferToImage(cb, upload_[i].buffer(), color_[i].image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        transitionImage(cb, color_[i].image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
    }
}

GBufferStorage GBufferPass::storage() const {
    if (!scene_.device().features().rayTracing) throw VulkanError("the G-buffer's targets are storage images on a ray-tracing device only");
    GBufferStorage s;
    s.width = width_;
    s.height = height_;
    for (int i = 0; i < kColorTargets; ++i) {
        s.images[i] = color_[i].image();
        s.views[i] = color_[i].view();
    }
    return s;
}

void GBufferPass::recordWrittenOnDevice(VkCommandBuffer cb) {
    // Written earlier on this queue (in the frame's command buffer or an earlier one), already in
    // VK_IMAGE_LAYOUT_GENERAL.
    VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_MEMORY_WRITE_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT};
    const VkPipelineStageFlags readers =
        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, readers, 0, 1, &b, 0, nullptr, 0, nullptr);
}

void GBufferPass::recordReadback(VkCommandBuffer cb, GBufferTargets targets) {
    const VulkanDevice& device = scene_.device();
    for (int i = 0; i <= kColorTargets; ++i) {
        if (!(targets & (1u << i))) continue;
        const bool isDepth = i == kColorTargets;
        const GpuImage& image = isDepth ? depth_ : color_[i];
        const std::size_t bytes = static_cast<std::size_t>(width_) * height_ * (isDepth ? 4 : texelBytes(kFormats[i]));
        if (!readback_[i].valid())
            readback_[i] = GpuBuffer(device, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuBuffer::Memory::HostVisible);
        recordCopyToBuffer(cb, image, isDepth ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT) : image.aspect(), readback_[i]);
    }
    recordHostReadBarrier(cb);
}

void GBufferPass::unpack(GBufferTargets targets, GBuffer& out) const {
    out.width = static_cast<int>(width_);
    out.height = static_cast<int>(height_);
    out.targets = targets;
    const std::size_t n = static_cast<std::size_t>(width_) * height_;
    std::array<std::vector<glm::vec4>*, kColorTargets> vec4Targets = {&out.position, &out.normal,   &out.emission, &out.ambient,
                                                                       &out.diffuse,  &out.specular, &out.optical,  nullptr};
    for (int i = 0; i <= kColorTargets; ++i) {
        const bool wanted = targets & (1u << i);
        if (i == kColorTargets) {
            out.depth.resize(wanted ? n : 0);
            if (wanted) std::memcpy(out.depth.data(), readback_[i].readBack(n * sizeof(float)), n * sizeof(float));
        } else if (kFormats[i] == VK_FORMAT_R32_UINT) {
            out.objectId.resize(wanted ? n : 0);
            if (wanted) std::memcpy(out.objectId.data(), readback_[i].readBack(n * sizeof(std::uint32_t)), n * sizeof(std::uint32_t));
        } else if (!wanted) {
            vec4Targets[i]->clear();
        } else if (kFormats[i] == VK_FORMAT_R32G32B32A32_SFLOAT) {
            vec4Targets[i]->resize(n);
            std::memcpy(vec4Targets[i]->data(), readback_[i].readBack(n * sizeof(glm::vec4)), n * sizeof(glm::vec4));
        } else {
            unpackHalf4(readback_[i].readBack(n * 4 * sizeof(std::uint16_t)), n, *vec4Targets[i]);
        }
    }
}

}  // namespace hybridlab
