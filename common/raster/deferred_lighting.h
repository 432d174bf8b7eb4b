#pragma once
// The deferred lighting pass (Walewski 2019 §3.1, Listing 5): a full-screen pass that evaluates
// the shading model's local term from the G-buffer (shaders/deferred_lighting.frag, the functions
// of common/raytrace/shading in GLSL, held equal by RasterLighting in tests/raster/test_raster_lighting.cpp) into an RGBA32F image, Walewski's P-buffer; the sky where nothing
// was hit; optionally shadow-map visibility, and environment-mapped reflection and refraction.
#include <array>

#include "common/image/image.h"
#include "common/raster/gbuffer_pass.h"
#include "common/raster/shadow_maps.h"
#include "common/scene/camera.h"

namespace hybridlab {

class DeferredLighting {
public:
    DeferredLighting(const GpuScene& scene, const GBufferPass& gbuffer, const ShadowMaps& shadows);

    // Renders the lighting of the G-buffer seen from `camera` (after GBufferPass::recordFinish()),
    // leaving the output in GENERAL.
    void record(VkCommandBuffer cb, const Camera& camera, const LightingOptions& options, const ShadowSettings& shadowSettings);
    void recordReadback(VkCommandBuffer cb);
    // The linear RGBA image after the commands completed (alpha 1).
    void unpack(Image& out) const;

    VkImageView output() const { return output_.view(); }

private:
    void resize(std::uint32_t width, std::uint32_t height);

    const GpuScene& scene_;
    const GBufferPass& gbuffer_;
    const ShadowMaps& shadows_;
    DescriptorSet descriptors_;
    UniquePipelineLayout layout_;
    std::array<UniquePipeline, 16> pipelines_;  // variants by option bits, created at first use
    UniqueSampler nearest_;
    GpuBuffer uniforms_, lights_;
    GpuImage output_;
    GpuBuffer readback_;
};

}  // namespace hybridlab
