#pragma once
// The screen-space reflection pass (de Macedo & Rodrigues §III, the reflection composer's first
// step): a Vulkan compute shader (shaders/ssr_trace.comp) recorded by the shared
// Rasterizer after lighting, marching every opaque reflective texel's mirror ray through the
// G-buffer's depth with McGuire & Mara's perspective-correct DDA and a thickness test. It reads
// back, per texel, the lit image at the hit, a confidence, and the reasons the ray failed: the mask
// of the texels the ray tracer completes.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "common/raster/frame_pass.h"
#include "common/raster/gpu_buffer.h"
#include "common/raster/gpu_image.h"
#include "common/raster/pipelines.h"
#include "techniques/ssr_fallback/shaders/ssr_records.h"

namespace hybridlab {

// The pass's defaults march to the ray's end; ssr_fallback's parameters default to a shorter Hi-Z
// march and a thinner slab, chosen on its speed-accuracy sweep (ssr_fallback_technique.cpp).
struct SsrSettings {
    enum class Traversal { Linear, HiZ };
    // The min-depth pyramid (FidelityFX SSSR) or the DDA pixel by pixel: the same hits, found
    // faster by the pyramid (measured by experiments/configs/ssr.toml).
    Traversal traversal = Traversal::HiZ;
    int maxSteps = 512;          // steps per ray (DDA steps, refinement steps, or pyramid cells visited)
    int stride = 1;              // linear: pixels per coarse step; a coarse hit is refined with unit steps
    // Depth of every visible surface's slab behind it, in view-depth units. Thinner than the
    // thinnest thing a scene shows (the 5 cm poles of thin-objects): a ray passing behind a thin
    // object is then a failure that the fallback traces, not a false hit on the object.
    float thickness = 0.02f;
    float maxDistance = 100.0f;  // world length of the ray
    float edgeFade = 0.05f;      // confidence ramps from 0 at the screen border over this fraction of the smaller side (0: none)
    bool refractive = false;     // also march the mirror rays of refractive texels (their Fresnel reflection)
};

struct SsrPixel {
    glm::vec3 color{0.0f};   // the lit image at the hit
    float confidence = 0.0f; // 0 where the ray failed; the screen-edge fade where it hit
    glm::ivec2 hit{-1, -1};  // the hit pixel, (-1, -1) without one
    std::uint32_t flags = 0;  // kSsrTraced, kSsr* failures (shaders/ssr_records.h)
    int steps = 0;

    bool traced() const { return (flags & kSsrTraced) != 0; }
    bool resolved() const { return traced() && (flags & kSsrFailures) == 0; }
};

// The pass's read-back, row-major like Image.
struct SsrResult {
    int width = 0, height = 0;
    std::vector<SsrPixel> pixels;
};

class SsrPass : public RasterFramePass {
public:
    // On `device`: the rasterizer's (the ray-tracing device's when the ray stage reads the outputs there).
    explicit SsrPass(std::shared_ptr<VulkanDevice> device = VulkanDevice::shared());

    // false: the pass records no copy of the outputs; they stay on the device (colorView(),
    // hitView()) unless the caller records recordReadback() into a command buffer of its own
    // after the frame's timed work.
    void setReadback(bool readback) { readback_ = readback; }
    // The outputs on the device: rgb the lit image at the hit, a confidence; xy hit pixel, z flags, w steps.
    VkImageView colorView() const { return color_.view(); }
    VkImageView hitView() const { return hit_.view(); }
    // The copies of the outputs to the host: recorded after the pass in the frame's command buffer
    // by the pass itself with setReadback(true) (finish() unpacks them), else by the caller after
    // the frame, who unpacks them with unpack() once that command buffer completed.
    void recordReadback(VkCommandBuffer cb);
    // The copied outputs into result().
    void unpack();

    void setSettings(const SsrSettings& settings) { settings_ = settings; }
    const SsrSettings& settings() const { return settings_; }

    std::string name() const override { return "ssr"; }
    void record(VkCommandBuffer cb, const FrameTargets& targets) override;
    void finish() override;

    // After the frame: the result of the last recorded frame.
    const SsrResult& result() const { return result_; }

private:
    void resize(std::uint32_t width, std::uint32_t height);
    void recordDepthPyramid(VkCommandBuffer cb, const FrameTargets& targets);

    std::shared_ptr<VulkanDevice> device_;
    SsrSettings settings_;
    bool readback_ = true;
    DescriptorSet descriptors_;
    UniquePipelineLayout layout_;
    std::array<UniquePipeline, 2> pipelines_;  // by traversal
    UniqueSampler nearest_;
    GpuBuffer uniforms_;
    GpuImage color_, hit_;
    // The min-depth pyramid of view depths (level 0 for the linear march, every level for hiz): one
    // descriptor set and storage view per level.
    GpuImage pyramid_;
    std::vector<UniqueImageView> pyramidLevels_;
    DescriptorSet pyramidDescriptors_;
    UniquePipelineLayout pyramidLayout_;
    std::array<UniquePipeline, 2> pyramidPipelines_;  // level 0 from the G-buffer, further levels
    GpuBuffer pyramidUniforms_;
    GpuBuffer colorReadback_, hitReadback_;
    // The texels to march, listed by the pyramid's level 0 (ssr_depth_pyramid.comp), with the indirect dispatch's size.
    GpuBuffer marchList_;
    SsrResult result_;
};

}  // namespace hybridlab
