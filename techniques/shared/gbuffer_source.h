#pragma once
// Where a hybrid technique's G-buffer comes from (its `gbuffer` parameter): the rasterizer's
// G-buffer pass (the papers' pipeline, the default), or primary rays on the ray backend
// (ray_cast_gbuffer.h, Falcor's GBufferRT) uploaded for the raster passes that read it (deferred
// lighting, SSR's depth pyramid and march). Every stage after the G-buffer is the same either way.
#include "common/raster/rasterizer.h"
#include "common/raytrace/ray_scene.h"
#include "common/raytrace/ray_stats.h"
#include "techniques/parameters.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

class GBufferSource {
public:
    static ParamSpec parameterSpec();
    explicit GBufferSource(const ParameterSet& p);

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

private:
    bool rays_ = false;
    GBuffer cast_;  // reused from frame to frame
};

}  // namespace hybridlab
