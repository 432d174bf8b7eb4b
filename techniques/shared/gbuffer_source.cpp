#include "techniques/shared/gbuffer_source.h"

#include "techniques/shared/ray_cast_gbuffer.h"

namespace hybridlab {

ParameterBinder<GBufferSourceParameters> gbufferSourceParameters() {
    ParameterBinder<GBufferSourceParameters> b;
    b.bind(&GBufferSourceParameters::rays,
           ParamSpec::choice("gbuffer", "raster", {"raster", "rays"},
                             "primary visibility: the rasterizer's G-buffer pass (the papers), or primary rays on the ray tracer, "
                             "uploaded for the raster passes that read the G-buffer (lighting, SSR)"),
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
    rayCastGBuffer(*rays, request.camera, request.width, request.height, kUploaded | (request.readback & kGBufferDepth), cast_, stats);
    if (clock) clock->lap("gbuffer.rays");
    request.hostGBuffer = &cast_;
    rasterizer.render(request, frame);
    return cast_;
}

}  // namespace hybridlab
