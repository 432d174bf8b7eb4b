#pragma once
// Where a hybrid technique's G-buffer comes from (its `gbuffer` parameter): the rasterizer's
// G-buffer pass (the papers' pipeline, the default), or primary rays on the ray backend (Falcor's
// GBufferRT): on Embree (ray_cast_gbuffer.h) uploaded for the raster passes that read it (deferred
// lighting, SSR's depth pyramid and march), on the ray-tracing Vulkan device
// (common/device_rays/device_gbuffer_caster.h) written into the rasterizer's targets where they
// lie. Every stage after the G-buffer is the same either way.
#include <memory>

#include "common/device_rays/device_gbuffer_caster.h"
#include "common/raster/rasterizer.h"
#include "common/raytrace/ray_scene.h"
#include "common/raytrace/ray_stats.h"
#include "techniques/parameter_binder.h"
#include "techniques/stage_clock.h"
#include "techniques/technique.h"

namespace hybridlab {

// The `gbuffer` parameter.
struct GBufferSourceParameters {
    bool rays{};  // gbuffer = "rays"
};
ParameterBinder<GBufferSourceParameters> gbufferSourceParameters();

class GBufferSource {
public:
    explicit GBufferSource(const GBufferSourceParameters& p) : rays_(p.rays) {}

    bool rays() const { return rays_; }

    // Renders `request` into `frame`. With rays, the G-buffer is first cast from `rays` (which must
    // be at the request's time; counted in `stats`, timed as stage "gbuffer.rays" when `clock` is
    // given) and replaces the rasterizer's G-buffer pass. Returns the G-buffer the later stages read:
    // the cast one, or frame.gbuffer (the request's read-back targets).
    const GBuffer& render(Rasterizer& rasterizer, const RayScene* rays, RasterRequest request, RasterFrame& frame, RayStats& stats,
                          StageClock* clock = nullptr);
    // The G-buffer from primary rays alone, `targets` of it at the request's camera and size (for a
    // frame that lights it on the host, without the rasterizer); counted and timed as render() does.
    const GBuffer& cast(const RayScene& rays, const RasterRequest& request, GBufferTargets targets, RayStats& stats,
                        StageClock* clock = nullptr);

    // rays = "vulkan": with rays, builds the device's caster over `rays` (compiling its pipeline).
    void prepareOnDevice(const DeviceRayScene& rays);
    // As render(), with `rasterizer` on the ray-tracing device: with rays, the G-buffer is cast on
    // the device (from the scene prepareOnDevice() was given, which must be at the request's time)
    // into the rasterizer's targets at the start of the frame's command buffer (one submission with
    // the rest of the frame), and the G-buffer pass is skipped.
    void renderOnDevice(Rasterizer& rasterizer, RasterRequest request, RasterFrame& frame, RayStats& stats);
    // After renderOnDevice(): the cast's GPU time as stage "gbuffer.rays" (none without rays), a
    // part of the frame's submission (lapRasterFrame).
    std::vector<StageTime> deviceCastStages() const;
    // After renderOnDevice() with rays: the cast's launch as counters (recordDeviceLaunch() of kind
    // "gbuffer.rays", device_rays.h); nothing without rays.
    void recordDeviceCast(FrameResult& result) const;

private:
    bool rays_ = false;
    GBuffer cast_;  // reused from frame to frame
    std::unique_ptr<DeviceGBufferCaster> deviceCaster_;
    DeviceGBufferCast deviceCast_;
};

}  // namespace hybridlab
