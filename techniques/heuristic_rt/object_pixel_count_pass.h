#pragma once
// heuristic_rt's visible pixels per object (Walewski 2019 §3.2's A) counted on the device
// (shaders/object_pixel_count.comp) inside the rasterizer's frame: with rays = "vulkan" the host
// reads back one count an object, not the object-id target.
#include <cstdint>
#include <memory>
#include <vector>

#include "common/raster/frame_pass.h"
#include "common/raster/gpu_buffer.h"
#include "common/raster/pipelines.h"

namespace hybridlab {

class ObjectPixelCountPass : public RasterFramePass {
public:
    ObjectPixelCountPass(std::shared_ptr<VulkanDevice> device, std::size_t objectCount);

    std::string name() const override { return "heuristic.visible_pixels"; }
    void record(VkCommandBuffer cb, const FrameTargets& targets) override;
    void finish() override;

    // After the frame: texels per object.
    const std::vector<std::uint64_t>& counts() const { return counts_; }

private:
    std::shared_ptr<VulkanDevice> device_;
    std::size_t objects_;
    DescriptorSet descriptors_;
    UniquePipelineLayout layout_;
    UniquePipeline pipeline_;
    UniqueSampler nearest_;
    GpuBuffer buffer_;  // the sky, then one count an object: device-local
    GpuBuffer onHost_;  // its copy, read by the host
    std::vector<std::uint64_t> counts_;
};

}  // namespace hybridlab
