#include "techniques/shared/gbuffer_source.h"

#include <stdexcept>

#include "techniques/shared/device_rays.h"
#include "techniques/shared/ray_cast_gbuffer.h"

namespace hybridlab {

ParameterBinder<GBufferSourceParameters> gbufferSourceParameters() {
    ParameterBinder<GBufferSourceParameters> b;
    b.bind(&GBufferSourceParameters::rays,
           ParamSpec::choice("gbuffer", "raster", {"raster", "rays"},
                             "primary visibility: the rasterizer's G-buffer pass (the papers), or primary rays on the ray backend "
                             "(`rays`) into the same targets, which the raster passes read (lighting, SSR)"),
           {false, true});
    return b;
}

const GBuffer& GBufferSource::render(Rasterizer& rasterizer, const RayScene* rays, RasterRequest request, RasterFrame& frame,
                                     RayStats& stats, StageClock* clock) {
    if (!rays_) {
        rasterizer.render(request, frame);
        return frame.gbuffer;
    }
    // Every colour target: the lighting pass reads them all; the depth target has no reader.
    constexpr GBufferTargets kUploaded = kGBufferPosition | kGBufferNormal | kGBufferMaterial | kGBufferObjectId;
    request.hostGBuffer = &cast(*rays, request, kUploaded | (request.readback & kGBufferDepth), stats, clock);
    rasterizer.render(request, frame);
    return cast_;
}

const GBuffer& GBufferSource::cast(const RayScene& rays, const RasterRequest& request, GBufferTargets targets, RayStats& stats,
                                   StageClock* clock) {
    rayCastGBuffer(rays, request.camera, request.width, request.height, targets, cast_, stats);
    if (clock) clock->lap("gbuffer.rays");
    return cast_;
}

void GBufferSource::prepareOnDevice(const DeviceRayScene& rays) {
    if (rays_ && !deviceCaster_) deviceCaster_ = std::make_unique<DeviceGBufferCaster>(rays);
}

void GBufferSource::renderOnDevice(Rasterizer& rasterizer, RasterRequest request, RasterFrame& frame, RayStats& stats) {
    if (!rays_) {
        rasterizer.render(request, frame);
        return;
    }
    if (!deviceCaster_) throw std::logic_error("GBufferSource: prepareOnDevice() first");
    if (request.first) throw std::logic_error("GBufferSource: the cast is the frame's first work");
    const GBufferStorage targets = rasterizer.gbufferStorage(request.width, request.height);
    request.first = [&](VkCommandBuffer cb) { deviceCaster_->record(cb, targets, request.camera); };
    request.deviceGBuffer = true;
    rasterizer.render(request, frame);
    deviceCast_ = deviceCaster_->lastCast();
    stats.primary += deviceCast_.primaryRays;
}

std::vector<StageTime> GBufferSource::deviceCastStages() const {
    if (!rays_) return {};
    return {{"gbuffer.rays", deviceCast_.gpuMilliseconds}};
}

void GBufferSource::recordDeviceCast(FrameResult& result) const {
    if (!rays_) return;
    RayStats primary;
    primary.primary = deviceCast_.primaryRays;
    recordDeviceLaunch("gbuffer.rays", primary, deviceCast_.invocations, deviceCast_.gpuMilliseconds, result);
}

}  // namespace hybridlab
