#pragma once
// A technique's own GPU pass over a frame's targets (DESIGN.md "A frame, as data": SSR as a compute
// shader, heuristic and EM passes), recorded by the Rasterizer into the frame's command buffer after
// the lighting pass, while the G-buffer and the lit image are still on the GPU, and timed with GPU
// timestamps under its name. The pass owns its pipelines, outputs and read-back buffers.
#include <array>
#include <string>

#include <glm/mat4x4.hpp>

#include "common/raster/gbuffer_pass.h"
#include "common/raster/vulkan_device.h"
#include "common/scene/camera.h"

namespace hybridlab {

// What a pass may read: every view is in VK_IMAGE_LAYOUT_GENERAL and its writes are visible to
// compute and fragment shaders and to copies.
struct FrameTargets {
    std::uint32_t width = 0, height = 0;
    Camera camera;
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};                                    // Camera::projectionMatrix (Vulkan clip, y down, reverse-Z)
    std::array<VkImageView, GBufferPass::kColorTargets> gbuffer{};  // by GBufferTarget bit index: position, normal, ... object id
    VkImageView lighting = VK_NULL_HANDLE;                          // the lit image (RGBA32F); null when lighting was not asked for
};

class RasterFramePass {
public:
    virtual ~RasterFramePass() = default;

    // The GPU stage name of the pass (RasterFrame::gpuStages).
    virtual std::string name() const = 0;
    // Records the pass and the copies of whatever it reads back (host-visible buffers, with a
    // transfer-to-host barrier).
    virtual void record(VkCommandBuffer cb, const FrameTargets& targets) = 0;
    // After the frame's commands completed: unpack the read-back.
    virtual void finish() {}
};

}  // namespace hybridlab
