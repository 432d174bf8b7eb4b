#pragma once
// `ssr_fallback`: screen-space reflections with a ray-traced fallback (de Macedo & Rodrigues,
// §III and Figure 1). Per frame: the shared G-buffer and deferred lighting (the shadow composer:
// shadow maps, or ray-traced shadow rays); SSR as a compute pass on the G-buffer (ssr_pass.h);
// Embree rays for the texels SSR failed on, from the G-buffer position, recursive like the
// reference, and for every refractive texel; the two reflection images merged and their seam
// blurred (seam_blur.h); the composition of the shading model (DESIGN.md).
// With `rays = "vulkan"` the frame stays on the ray-tracing device: the rasterizer (or with
// `gbuffer = "rays"` the primary rays, into its targets) and SSR run there,
// the ray-traced stage reads the G-buffer, the lit image and SSR's outputs where they lie
// (shaders/device_ssr_fallback.rgen), the seam blur and composite follow as a compute pass
// (device_seam_composite.h), and the host reads back the final image (SSR's outputs and the
// per-texel terms only for the debug images and SSR's statistics, after the timed stages).
#include <memory>
#include <vector>

#include "common/raster/rasterizer.h"
#include "common/raytrace/whitted_tracer.h"
#include "common/device_rays/device_gbuffer_tracer.h"
#include "techniques/ssr_fallback/device_seam_composite.h"
#include "techniques/ssr_fallback/seam_blur.h"
#include "techniques/ssr_fallback/shaders/ssr_texel.h"
#include "techniques/shared/device_launch_parameters.h"
#include "techniques/shared/gbuffer_source.h"
#include "techniques/shared/raster_warm_up.h"
#include "techniques/shared/ray_backend_parameters.h"
#include "techniques/shared/recursion_parameters.h"
#include "techniques/shared/shadow_parameters.h"
#include "techniques/ssr_fallback/ssr_pass.h"
#include "techniques/technique.h"

namespace hybridlab {

struct SsrFallbackParameters;

class SsrFallbackTechnique : public Technique {
public:
    static TechniqueInfo info();
    explicit SsrFallbackTechnique(const SsrFallbackParameters& params);

    // Builds the ray scene, creates the SSR pass and renders one small frame (lavapipe compiles
    // shaders at their first use).
    void prepare(SceneContext& context) override;
    FrameResult render(SceneContext& context, const FrameRequest& frame) override;

    enum class Fallback { RayTraced, Sky, None };
    enum class Recursion { RayTraced, Single };

private:
    RasterRequest rasterRequest(const FrameRequest& frame);
    FrameResult renderOnDevice(SceneContext& context, const FrameRequest& frame);
    // The stage's settings, for both backends (the device reads them packed, packSsrOptions).
    shading_language::SsrTexelPolicy texelPolicy() const;
    // SSR's work and the debug images of SSR's outputs (the same for both backends).
    void recordSsrStatistics(const std::vector<ReflectionSource>& source, const std::vector<std::uint8_t>& refractive, FrameResult& result) const;

    bool onDevice_ = false;  // rays = "vulkan"

    DeviceLaunchParameters launch_; // with rays = "vulkan"
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
    std::unique_ptr<DeviceGBufferTracer> deviceTracer_;  // rays = "vulkan"
    std::unique_ptr<DeviceSeamComposite> deviceComposite_;
};

struct SsrFallbackParameters {
    bool ssr{};
    bool rayTracedShadows{};  // shadows = "rt"
    SsrFallbackTechnique::Fallback fallback{};
    bool glassBySsr{};  // glass = "ssr"
    SsrFallbackTechnique::Recursion hitRecursion{};
    SsrSettings::Traversal traversal{};
    int maxSteps{};
    int stride{};
    float thickness{};
    float maxDistance{};
    float edgeFade{};
    int blurRadius{};
    float blurRange{};
    GBufferSourceParameters gbuffer;
    RayBackendParameters rays;
    DeviceLaunchParameters launch;
    ShadowMapParameters shadowMaps;
    RecursionParameters recursion;
};

}  // namespace hybridlab
