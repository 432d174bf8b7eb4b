#pragma once
// `ssr_fallback`: screen-space reflections with a ray-traced fallback (de Macedo & Rodrigues,
// §III and Figure 1). Per frame: the shared G-buffer and deferred lighting (the shadow composer:
// shadow maps, or ray-traced shadow rays); SSR as a compute pass on the G-buffer (ssr_pass.h);
// Embree rays for the texels SSR failed on, from the G-buffer position, recursive like the
// reference, and for every refractive texel; the two reflection images merged and their seam
// blurred (seam_blur.h); the composition of the shading model (DESIGN.md).
#include <memory>
#include <vector>

#include "common/raster/rasterizer.h"
#include "common/raytrace/whitted_tracer.h"
#include "techniques/ssr_fallback/seam_blur.h"
#include "techniques/shared/gbuffer_source.h"
#include "techniques/shared/raster_warm_up.h"
#include "techniques/ssr_fallback/ssr_pass.h"
#include "techniques/technique.h"

namespace hybridlab {

class SsrFallbackTechnique : public Technique {
public:
    static TechniqueInfo info();
    explicit SsrFallbackTechnique(const ParameterSet& params);

    // Builds the ray scene, creates the SSR pass and renders one small frame (lavapipe compiles
    // shaders at their first use).
    void prepare(SceneContext& context) override;
    FrameResult render(SceneContext& context, const FrameRequest& frame) override;

    enum class Fallback { RayTraced, Sky, None };
    enum class Recursion { RayTraced, Single };

private:
    RasterRequest rasterRequest(const FrameRequest& frame);

    bool ssrOn_ = true;
    bool rayTracedShadows_ = false;
    Fallback fallback_ = Fallback::RayTraced;
    Recursion recursion_ = Recursion::RayTraced;
    int blurRadius_ = 2;
    float blurRange_ = 0.1f;
    SsrSettings ssrSettings_;
    ShadowSettings shadowSettings_;
    WhittedSettings tracerSettings_;
    std::unique_ptr<SsrPass> ssr_;
    RasterFrame raster_;  // reused between frames
    GBufferSource gbuffer_;
    RasterWarmUp warmUp_;
};

}  // namespace hybridlab
