#pragma once
// The layered-EM lens pass (Hakura & Snyder 2001 §5, "Multipass Rendering with Layered EM
// Indexing", in one pass with programmable shading as the paper's closing remark suggests): a
// Vulkan draw recorded by the shared Rasterizer after lighting (common/raster/frame_pass.h). Each
// lens system's tessellated lens is drawn with its per-vertex attributes (lens_draw.h) into the
// pass's own colour and depth targets (shaders layered_em.vert, layered_em.frag): per term and
// layer the inferred cube map read at the interpolated index, layers composited front to back,
// the sky behind, times F G, the terms summed, the two nearest viewpoint samples blended.
// Fragments behind the surface the G-buffer shows are discarded. The read-back is the lens
// radiance with alpha 1 where the lens shows.
#include <memory>
#include <vector>

#include "common/image/image.h"
#include "common/raster/frame_pass.h"
#include "common/raster/gpu_buffer.h"
#include "common/raster/gpu_image.h"
#include "common/raster/pipelines.h"
#include "techniques/layered_em/lens_draw.h"

namespace hybridlab {

// One lens system to draw this frame.
struct LensDraw {
    const LensDrawGeometry* geometry = nullptr;
    const LayeredEm* em = nullptr;
    ViewpointBlend blend;
};

class LayeredEmPass : public RasterFramePass {
public:
    LayeredEmPass();

    // The systems of the next recorded frame (the pointers must stay valid until finish()).
    void setDraws(std::vector<LensDraw> draws) { draws_ = std::move(draws); }
    // The cube maps stay on the device while the draws' (EM, samples) do not change; call this when
    // the EMs the draws point to are replaced (a new EM may take an old one's address).
    void forgetResidentTexels() { residentTexels_.clear(); }

    std::string name() const override { return "lens.draw"; }
    void record(VkCommandBuffer cb, const FrameTargets& targets) override;
    void finish() override;

    // After the frame: the lens radiance, alpha 1 where a lens fragment was drawn, 0 elsewhere.
    const Image& result() const { return result_; }

private:
    void resize(std::uint32_t width, std::uint32_t height);
    void upload();

    std::shared_ptr<VulkanDevice> device_;
    std::vector<LensDraw> draws_;
    // The G-buffer occlusion test's tolerance, relative to the fragment's distance from the eye.
    static constexpr float kOcclusionTolerance = 2e-3f;
    DescriptorSet descriptors_;
    UniquePipelineLayout layout_;
    UniquePipeline pipeline_;
    UniqueSampler nearest_;
    GpuImage color_, depth_;
    GpuBuffer vertices_, indices_, texels_, readback_;
    // Per draw: first index, index count, first vertex, first texel of viewpoint samples A and B.
    struct Range {
        std::uint32_t firstIndex = 0, indexCount = 0;
        std::int32_t firstVertex = 0;
        std::int32_t texelsA = 0, texelsB = 0;
    };
    std::vector<Range> ranges_;
    // Per draw, whose cube maps texels_ holds.
    struct ResidentTexels {
        const LayeredEm* em = nullptr;
        std::size_t a = 0, b = 0;
        bool operator==(const ResidentTexels&) const = default;
    };
    std::vector<ResidentTexels> residentTexels_;
    Image result_;
};

}  // namespace hybridlab
