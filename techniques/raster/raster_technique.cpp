#include "techniques/raster/raster_technique.h"

#include <algorithm>

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
    FrameRequest warmUp{context.scene().camera, 0.0, 64, 36};
    context.rasterizer().render(request(warmUp), frame_);
}

FrameResult RasterTechnique::render(SceneContext& context, const FrameRequest& frame) {
    if (frame.width != warmWidth_ || frame.height != warmHeight_) {
        context.rasterizer().render(request(frame), frame_);
        warmWidth_ = frame.width;
        warmHeight_ = frame.height;
    }
    context.rasterizer().render(request(frame), frame_);
    FrameResult result;
    // GPU timestamps per pass; the read-back includes unpacking on the CPU; what the timestamps do
    // not cover (recording, submission, waking up) is `overhead`, so the stages add up to the wall clock.
    double gpu = 0.0;
    for (const RasterStageTime& s : frame_.gpuStages) {
        gpu += s.milliseconds;
        result.stages.push_back({s.name, s.milliseconds + (s.name == "readback" ? frame_.unpackMilliseconds : 0.0)});
    }
    result.stages.push_back({"overhead", frame_.recordMilliseconds + std::max(0.0, frame_.submitMilliseconds - gpu)});
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
