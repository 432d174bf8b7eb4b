#pragma once
// Primary visibility on the ray-tracing device (Falcor's GBufferRT beside its GBufferRaster): one
// camera ray through every pixel centre, traced by the device's ray-tracing pipeline
// (shaders/device_gbuffer_cast.rgen), its hit written straight into the rasterizer's G-buffer
// targets where they lie, in the G-buffer pass's encoding (shaders/gbuffer_encoding.glsl). The
// rasterizer then skips its G-buffer pass (RasterRequest::deviceGBuffer) and its lighting, the
// technique's passes and the G-buffer tracer read the cast targets unchanged. The device's
// counterpart of rayCastGBuffer (techniques/shared/ray_cast_gbuffer.h); nothing goes through the host.
#include <cstdint>

#include "common/device_rays/device_ray_pipeline.h"
#include "common/raster/gbuffer_pass.h"
#include "common/scene/camera.h"

namespace hybridlab {

struct DeviceGBufferCast {
    std::uint64_t primaryRays = 0;  // counted on the device: one a pixel
    DeviceInvocations invocations;
    double gpuMilliseconds = 0.0;   // the launch's GPU timestamps
};

class DeviceGBufferCaster {
public:
    // Compiles (once per process) and binds the pipeline over `scene`, which must be at the frame's
    // time when cast() runs (DeviceRayScene::setTime).
    explicit DeviceGBufferCaster(const DeviceRayScene& scene);

    // Records the cast of `camera`'s primary rays at targets.width x targets.height into `targets`
    // (the rasterizer's, Rasterizer::gbufferStorage(), on this device) into `cb`, the frame's
    // command buffer, leaving them in VK_IMAGE_LAYOUT_GENERAL; the sky's texels all zero.
    void record(VkCommandBuffer cb, const GBufferStorage& targets, const Camera& camera);
    // After the command buffer record() went into completed: its counts and GPU time.
    DeviceGBufferCast lastCast() const;
    // record() in a submission of its own, waited for; lastCast().
    DeviceGBufferCast cast(const GBufferStorage& targets, const Camera& camera);

private:
    const DeviceRayScene& scene_;
    DeviceRayPipeline pipeline_;
};

}  // namespace hybridlab
