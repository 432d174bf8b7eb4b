#pragma once
// ssr_fallback's seam blur and composite on the device (shaders/ssr_composite.comp), recorded after
// the ray-traced stage in its command buffer (rays = "vulkan"): as blurReflectionSeams
// (seam_blur.h) and of the composition that follows it, over the terms the ray-generation shader
// left per texel, writing the frame's image where it lies.
#include <cstdint>

#include "common/raster/gpu_buffer.h"
#include "common/raster/pipelines.h"

namespace hybridlab {

class DeviceSeamComposite {
public:
    explicit DeviceSeamComposite(const VulkanDevice& device);

    // Blurs the seams of `texels` (DeviceGBufferTracer::texels(): M and its source, C and o_m, R and
    // o_r, flags) with seam_blur.h's radius and range, composes every composer texel into `image`.
    void record(VkCommandBuffer cb, const GpuBuffer& texels, const GpuBuffer& image, int width, int height, int radius, float rangeSigma,
                bool walewskiBlend);
    // After the command buffer completed: the texels blurred.
    std::uint32_t blurredTexels() const { return *counter_.readBack<std::uint32_t>(1); }

private:
    const VulkanDevice& device_;
    DescriptorSet descriptors_;
    UniquePipelineLayout layout_;
    UniquePipeline pipeline_;
    GpuBuffer uniforms_, counter_;
};

}  // namespace hybridlab
