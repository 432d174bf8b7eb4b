#pragma once
// The G-buffer pass (Walewski 2019 §3.1, Table 2): every object drawn once into eight render
// targets and a 32-bit float reverse-Z depth buffer (Upchurch & Desbrun; cleared to 0, depth test
// GREATER), sampling at pixel centres with the camera's projection, so that each texel holds the
// surface the reference's primary ray through that pixel centre hits. A depth-only pre-pass comes
// first, so that the material shader runs once per pixel (depth test EQUAL) however deep the
// overdraw: on lavapipe the shader, not the rasterization, is what costs. Also the depth-equal pass
// with one precise occlusion query per object (Walewski 2019 Listing 6), and the read-back of the
// targets a technique asks for.
#include <array>

#include "common/raster/gbuffer.h"
#include "common/raster/gpu_image.h"
#include "common/raster/gpu_scene.h"

namespace hybridlab {

struct GBufferStorage;

class GBufferPass {
public:
    static constexpr int kColorTargets = 8;  // position, normal, emission, ambient, diffuse, specular, optical, object id

    explicit GBufferPass(const GpuScene& scene);

    // (Re)creates the targets for a width x height frame; a no-op when the size is unchanged.
    void resize(std::uint32_t width, std::uint32_t height);
    std::uint32_t width() const { return width_; }
    std::uint32_t height() const { return height_; }

    // Clears and renders the G-buffer; returns the number of draws. Leaves every target in
    // VK_IMAGE_LAYOUT_GENERAL, readable by later passes and by copies, after recordFinish().
    std::size_t record(VkCommandBuffer cb, const glm::mat4& viewProj);
    // The depth-equal pass: each object drawn again with depth test EQUAL and no writes inside its
    // own precise occlusion query (query i = object i of `queries`). Between record() and recordFinish().
    void recordVisiblePixelQueries(VkCommandBuffer cb, const glm::mat4& viewProj, VkQueryPool queries);
    // Moves the targets to GENERAL for sampling and copying.
    void recordFinish(VkCommandBuffer cb);

    // Instead of record() and recordFinish(): fills the colour targets from a G-buffer made on the host
    // (primary rays, techniques/shared/ray_cast_gbuffer.h; it must hold every colour target), packed
    // into their formats and copied up, leaving them in VK_IMAGE_LAYOUT_GENERAL as recordFinish()
    // does, for the lighting and a technique's passes. The depth buffer is not filled: no later
    // pass reads it (SSR builds its depth pyramid from the position target).
    void recordUpload(VkCommandBuffer cb, const GBuffer& host);

    // On a ray-tracing device the colour targets are storage images too (storage()): a G-buffer
    // written there by primary rays replaces record() and recordFinish(), and
    // recordWrittenOnDevice() makes its writes visible to the frame's passes and copies.
    GBufferStorage storage() const;
    void recordWrittenOnDevice(VkCommandBuffer cb);

    // Copies `targets` into host-visible buffers (after recordFinish()); unpack() fills a GBuffer
    // from them once the commands completed.
    void recordReadback(VkCommandBuffer cb, GBufferTargets targets);
    void unpack(GBufferTargets targets, GBuffer& out) const;

    // The view of colour target i (0 position ... 7 object id).
    VkImageView targetView(int i) const { return color_[i].view(); }

private:
    const GpuScene& scene_;
    UniquePipelineLayout layout_;
    // Variants by the material's textures: bit 0 diffuse texture, bit 1 normal map.
    std::array<UniquePipeline, 4> pipelines_;
    std::vector<int> drawVariant_;  // per GpuScene draw
    UniquePipeline prepassPipeline_;  // depth only
    UniquePipeline queryPipeline_;
    std::uint32_t width_ = 0, height_ = 0;
    std::array<GpuImage, kColorTargets> color_;
    GpuImage depth_;
    std::array<GpuBuffer, kColorTargets + 1> readback_;  // by target bit index; allocated on first use
    std::array<GpuBuffer, kColorTargets> upload_;        // recordUpload's staging, by target; allocated on first use
};

// The G-buffer's colour targets for a G-buffer written on the device by another pipeline (primary
// rays: common/device_rays/device_gbuffer_caster.h) before the frame that reads it
// (RasterRequest::deviceGBuffer): storage images of the formats gbuffer_pass.cpp gives them, in
// whatever layout the last frame left them (the writer moves them to VK_IMAGE_LAYOUT_GENERAL).
struct GBufferStorage {
    std::uint32_t width = 0, height = 0;
    std::array<VkImage, GBufferPass::kColorTargets> images{};  // by GBufferTarget bit index
    std::array<VkImageView, GBufferPass::kColorTargets> views{};
};

}  // namespace hybridlab
