#include "techniques/raster/raster_technique.h"

#include "techniques/make_technique_info.h"
#include "techniques/shared/blend_parameter.h"
#include "techniques/shared/raster_stages.h"
#include "techniques/shared/raster_work_counters.h"
#include "techniques/shared/shadow_parameters.h"

namespace hybridlab {

TechniqueInfo RasterTechnique::info() {
    ParameterBinder<RasterParameters> parameters;
    parameters.bind(&RasterParameters::shadows,
                    ParamSpec::choice("shadows", "map", {"map", "off"}, "shadow maps with PCF, or every light unshadowed"), {true, false});
    parameters.bind(&RasterParameters::shadowMaps, shadowMapParameters());
    parameters.bind(&RasterParameters::redrawShadowMaps,
                    ParamSpec::boolean("redraw_shadow_maps", false,
                                       "redraw shadow maps every frame (false: only when something moved or the settings changed)"));
    parameters.bind(&RasterParameters::blend, blendParameterSpec(), blendParameterValues());
    return makeTechniqueInfo(
        "raster", "Rasterization only (headless Vulkan): G-buffer, deferred Blinn-Phong lighting, shadow maps, sky environment mapping",
        std::move(parameters), [](const RasterParameters& p) { return std::make_unique<RasterTechnique>(p); },
        /*relativeCost=*/0.2);  // 0.06-0.33 of the reference at 320x180 on lavapipe (whitted-classic, cornell-mirror-glass)
}

RasterTechnique::RasterTechnique(const RasterParameters& p) {
    lighting_.shadows = p.shadows;
    lighting_.environmentMapping = true;
    lighting_.walewskiBlend = p.blend == BlendRule::Walewski2019;
    shadows_ = p.shadowMaps.settings();
    redrawShadowMaps_ = p.redrawShadowMaps;
}

RasterRequest RasterTechnique::request(const FrameRequest& frame) const {
    RasterRequest r = frame.rasterRequest();
    r.lighting = true;
    r.lightingOptions = lighting_;
    r.shadowSettings = shadows_;
    r.redrawShadowMaps = redrawShadowMaps_;
    return r;
}

void RasterTechnique::prepare(SceneContext& context) {
    context.rasterizer().render(request(RasterWarmUp::preparing(context.scene())), frame_);
}

FrameResult RasterTechnique::render(SceneContext& context, const FrameRequest& frame) {
    warmUp_.atSizeOf(frame, [&](const FrameRequest& f) { context.rasterizer().render(request(f), frame_); });
    FrameResult result;
    StageClock clock(result);
    context.rasterizer().render(request(frame), frame_);
    lapRasterFrame(clock, frame_);
    result.image = std::move(frame_.lighting);
    result.counters["draws"] = static_cast<double>(frame_.draws);
    recordRasterWork(frame_, result);
    result.counters["shadow_maps_drawn"] = frame_.shadowMapsDrawn ? 1.0 : 0.0;
    result.counters["wall_ms"] = frame_.wallMilliseconds();
    result.counters["rays_total"] = 0.0;
    result.counters["pixels_ray_traced"] = 0.0;
    return result;
}

}  // namespace hybridlab
