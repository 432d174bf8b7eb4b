#pragma once
// `raster`: rasterization only, nothing ray traced (DESIGN.md; the floor of every speed-accuracy
// chart). The shared rasterizer's G-buffer and deferred lighting with shadow maps; reflective and
// refractive pixels look up the sky in the reflected and refracted directions (environment
// mapping, Blinn & Newell 1976) and compose by the shading model, so the baseline is the usual
// raster answer rather than black.
#include "common/raster/rasterizer.h"
#include "common/raytrace/shading.h"
#include "techniques/shared/raster_warm_up.h"
#include "techniques/shared/shadow_parameters.h"
#include "techniques/technique.h"

namespace hybridlab {

struct RasterParameters {
    bool shadows{};  // shadows = "map"
    ShadowMapParameters shadowMaps;
    bool redrawShadowMaps{};
    BlendRule blend{};
};

class RasterTechnique : public Technique {
public:
    static TechniqueInfo info();
    explicit RasterTechnique(const RasterParameters& params);

    // Uploads the scene and renders one small frame: lavapipe compiles shaders at their first draw,
    // which would otherwise land in the first frame's times. Static shadow maps are drawn here too.
    void prepare(SceneContext& context) override;
    // The first frame at a new size is rendered twice and the second one timed (new targets cost
    // page faults and allocations the steady state does not pay).
    FrameResult render(SceneContext& context, const FrameRequest& frame) override;

private:
    RasterRequest request(const FrameRequest& frame) const;

    LightingOptions lighting_;
    ShadowSettings shadows_;
    bool redrawShadowMaps_ = false;
    RasterFrame frame_;  // reused between frames
    RasterWarmUp warmUp_;
};

}  // namespace hybridlab
