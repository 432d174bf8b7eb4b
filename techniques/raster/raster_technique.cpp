#include "techniques/raster/raster_technique.h"

#include "techniques/shared/raster_stages.h"
#include "techniques/shared/raster_work_counters.h"
#include "techniques/shared/shadow_parameters.h"

namespace hybridlab {

TechniqueInfo RasterTechnique::info() {
    TechniqueInfo info{"raster",
            "Rasterization only (headless Vulkan): G-buffer, deferred Blinn-Phong lighting, shadow maps, sky environment mapping",
            {
                ParamSpec::choice("shadows", "map", {"map", "off"}, "shadow maps with PCF, or every light unshadowed"),
                ParamSpec::boolean("redraw_shadow_maps", false,
                                   "redraw shadow maps every frame (false: only when something moved or the settings changed)"),
                ParamSpec::choice("blend", "design", {"design", "walewski2019"},
                                  "composition rule: design = o_m*M + (1-o_m)*(o_r*R + (1-o_r)*C) (o_m reflectivity or Fresnel, "
                                  "o_r 1-opacity), or walewski2019 = that averaged with the other order (Walewski 2019 eqs. (5)-(6))"),
            },
            [](const ParameterSet& p) { return std::make_unique<RasterTechnique>(p); },
            /*relativeCost=*/0.2};  // 0.06-0.33 of the reference at 320x180 on lavapipe (whitted-classic, cornell-mirror-glass)
    const std::vector<ParamSpec> shadowMaps = shadowMapParameterSpecs();
    info.parameters.insert(info.parameters.begin() + 1, shadowMaps.begin(), shadowMaps.end());  // after "shadows"
    return info;
}

RasterTechnique::RasterTechnique(const ParameterSet& p) {
    lighting_.shadows = p.getChoice("shadows") == "map";
    lighting_.environmentMapping = true;
    lighting_.walewskiBlend = p.getChoice("blend") == "walewski2019";
    shadows_ = shadowMapSettings(p);
    redrawShadowMaps_ = p.getBool("redraw_shadow_maps");
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
