#pragma once
// Where a hybrid technique's G-buffer comes from (its `gbuffer` parameter): the rasterizer's
// G-buffer pass (the papers' pipeline, the default), or primary rays on the ray backend
// (ray_cast_gbuffer.h, Falcor's GBufferRT) uploaded for the raster passes that read it (deferred
// lighting, SSR's depth pyramid and march). Every stage after the G-buffer is the same either way.
#include "common/raster/rasterizer.h"
#include "common/raytrace/ray_scene.h"
#include "common/raytrace/ray_stats.h"
#include "techniques/parameter_binder.h"
#include "techniques/stage_clock.h"

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

private:
    bool rays_ = false;
    GBuffer cast_;  // reused from frame to frame
};

}  // namespace hybridlab
