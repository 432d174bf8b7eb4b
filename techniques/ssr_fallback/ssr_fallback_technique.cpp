#include "techniques/ssr_fallback/ssr_fallback_technique.h"

#include <algorithm>
#include <atomic>
#include <optional>

#include "common/raytrace/embree_tree_backend.h"
#include "techniques/make_technique_info.h"
#include "techniques/shared/device_rays.h"
#include "techniques/shared/gbuffer_surface.h"
#include "techniques/shared/pixel_loop.h"
#include "techniques/shared/raster_stages.h"
#include "techniques/shared/raster_work_counters.h"
#include "techniques/shared/ray_counters.h"
#include "techniques/shared/ray_scene_update.h"
#include "techniques/ssr_fallback/shaders/ssr_texel.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

namespace {

namespace sl = shading_language;

// Per texel, what the reflection composer needs after the ray-traced stage.
struct ReflectiveTexel {
    sl::HitParts parts;
    bool composed = false;  // the texel takes part in the reflection composer
};

// The paper's Figure 2 colours the texels by the path of their reflection: blue SSR, pink ray traced.
glm::vec4 sourceColor(ReflectionSource s, bool refractive) {
    if (refractive) return {0.6f, 0.2f, 0.5f, 1.0f};  // ray traced whole (SSR does not refract)
    switch (s) {
        case ReflectionSource::Ssr: return {0.2f, 0.4f, 1.0f, 1.0f};
        case ReflectionSource::RayTraced: return {1.0f, 0.4f, 0.8f, 1.0f};
        case ReflectionSource::Sky: return {0.4f, 1.0f, 1.0f, 1.0f};
        case ReflectionSource::Missing: return {0.15f, 0.15f, 0.15f, 1.0f};
        case ReflectionSource::None: break;
    }
    return {0.0f, 0.0f, 0.0f, 1.0f};
}

// The failure mask as colours: red off screen, green behind a surface, blue out of steps, yellow
// back face, magenta maximum distance (reasons add); white where SSR hit; black where it did not run.
glm::vec4 failureColor(std::uint32_t flags) {
    if (!(flags & kSsrTraced)) return {0.0f, 0.0f, 0.0f, 1.0f};
    if (!(flags & kSsrFailures)) return {1.0f, 1.0f, 1.0f, 1.0f};
    glm::vec3 c(0.0f);
    if (flags & kSsrOffScreen) c += glm::vec3(1, 0, 0);
    if (flags & kSsrBehind) c += glm::vec3(0, 1, 0);
    if (flags & kSsrOutOfSteps) c += glm::vec3(0, 0, 1);
    if (flags & kSsrBackFace) c += glm::vec3(1, 1, 0);
    if (flags & kSsrMaxDistance) c += glm::vec3(1, 0, 1);
    return glm::vec4(glm::min(c, glm::vec3(1.0f)), 1.0f);
}

// The march's defaults, from the speed-accuracy sweep (README.md "Defaults"): on every scene swept,
// at 320x180 and at 1280x720, the hits a Hi-Z march finds past 64 cells and in a slab deeper than
// 1 cm lower SSIM or leave it (the fallback's rays are exact where SSR's lit image is not), while
// the old defaults (512, 2 cm) cost the SSR pass up to 3.5x the steps at 1280x720. SsrSettings
// keeps the pass's own defaults, a march to the ray's end, which a linear march (steps are pixels)
// needs and the pass's tests exercise.
constexpr int kMarchMaxSteps = 64;
constexpr double kMarchThickness = 0.01;

}  // namespace

TechniqueInfo SsrFallbackTechnique::info() {
    using P = SsrFallbackParameters;
    using Traversal = SsrSettings::Traversal;
    const SsrSettings d;
    ParameterBinder<P> parameters;
    parameters.bind(&P::ssr, ParamSpec::boolean("ssr", true, "run SSR (false: every reflective texel takes the fallback)"));
    parameters.bind(&P::rayTracedShadows,
                    ParamSpec::choice("shadows", "map", {"map", "rt"}, "shadow composer: shadow maps, or ray-traced shadow rays"), {false, true});
    parameters.bind(&P::fallback,
                    ParamSpec::choice("fallback", "rt", {"rt", "sky", "none"},
                                      "where SSR fails: ray tracing, the sky in the reflected direction, or no reflection (HDRP's chain)"),
                    {Fallback::RayTraced, Fallback::Sky, Fallback::None});
    parameters.bind(&P::glassBySsr,
                    ParamSpec::choice("glass", "rt", {"rt", "ssr"},
                                      "refractive texels: ray trace everything, or take their Fresnel reflection from SSR as opaque "
                                      "mirrors do (with the same fallback) and ray trace only the refraction"),
                    {false, true});
    parameters.bind(&P::hitRecursion,
                    ParamSpec::choice("recursion", "rt", {"rt", "single"},
                                      "an SSR hit on a reflective or refractive surface: ray trace its next bounce, or take the lit image"),
                    {Recursion::RayTraced, Recursion::Single});
    parameters.bind(&P::traversal,
                    ParamSpec::choice("traversal", d.traversal == Traversal::HiZ ? "hiz" : "linear", {"linear", "hiz"},
                                      "SSR: the perspective-correct DDA pixel by pixel, or the hierarchical min-depth traversal"),
                    {Traversal::Linear, Traversal::HiZ});
    parameters.bind(&P::maxSteps, ParamSpec::integer("max_steps", kMarchMaxSteps, 1, 16384,
                                                     "SSR: steps per ray (pyramid cells for hiz; pixels for linear, whose march across "
                                                     "the image needs its width, e.g. 512)"));
    parameters.bind(&P::stride,
                    ParamSpec::integer("stride", d.stride, 1, 64, "SSR: pixels per coarse step (a coarse hit is refined with unit steps)"));
    parameters.bind(&P::thickness, ParamSpec::real("thickness", kMarchThickness, 0.0, 1e6,
                                                   "SSR: depth of the slab behind every visible surface (view depth, world units)"));
    parameters.bind(&P::maxDistance, ParamSpec::real("max_distance", d.maxDistance, 0.0, 1e9, "SSR: world length of a reflection ray"));
    parameters.bind(&P::edgeFade, ParamSpec::real("edge_fade", d.edgeFade, 0.0, 0.5,
                                                  "SSR: confidence ramps up over this fraction of the screen from its border (0: no fade)"));
    parameters.bind(&P::blurRadius,
                    ParamSpec::integer("blur_radius", 2, 0, 16, "seam blur radius in pixels between SSR and ray-traced reflections (0: off)"));
    parameters.bind(&P::blurRange, ParamSpec::real("blur_range", 0.1, 0.0, 1.0,
                                                   "seam blur: bilateral range sigma on c / (1 + c) colours (0: the paper's plain Gaussian, "
                                                   "which smears thin reflected detail)"));
    parameters.bind(&P::gbuffer, gbufferSourceParameters());
    parameters.bind(&P::rays, rayBackendParameters());
    parameters.bind(&P::launch, deviceLaunchParameters());
    parameters.bind(&P::shadowMaps, shadowMapParameters());
    // The fallback rays recurse as the reference's (max_depth, importance_cutoff, blend), cut off at
    // rt_only's importance: the full trees (0) cost 3.7x the rays for the same SSIM (README.md).
    parameters.bind(&P::recursion, recursionParameters(kTracedImportanceCutoff));
    TechniqueInfo info = makeTechniqueInfo(
        "ssr_fallback",
        "de Macedo & Rodrigues: screen-space reflections (Vulkan compute, McGuire-Mara DDA) with a ray-traced fallback for the "
        "texels SSR fails on, seam blur",
        std::move(parameters), [](const P& p) { return std::make_unique<SsrFallbackTechnique>(p); },
        /*relativeCost=*/0.35);  // 0.20-0.42 of the reference at 320x180 (whitted-classic, cornell-mirror-glass)
    // SSR's march (steps and slab thickness, ssr_fallback_sweep.toml's ranges) and the fallback's
    // ray-tree cut-off.
    using S = SearchDimension::Scale;
    info.searchSpace = {{"max_steps", {16LL, 32LL, 64LL, 128LL, 256LL}, S::Log},
                        {"thickness", {0.005, 0.01, 0.02, 0.04, 0.08}, S::Log},
                        {"importance_cutoff", {0.0, 0.05}, S::Linear}};
    return info;
}

SsrFallbackTechnique::SsrFallbackTechnique(const SsrFallbackParameters& p)
    : onDevice_(p.rays.onDevice),
      launch_(p.launch),
      ssrOn_(p.ssr),
      rayTracedShadows_(p.rayTracedShadows),
      fallback_(p.fallback),
      recursion_(p.hitRecursion),
      blurRadius_(p.blurRadius),
      blurRange_(p.blurRange),
      shadowSettings_(p.shadowMaps.settings()),
      tracerSettings_(p.recursion.settings()),
      gbuffer_(p.gbuffer) {
    ssrSettings_.refractive = p.glassBySsr;
    ssrSettings_.traversal = p.traversal;
    ssrSettings_.maxSteps = p.maxSteps;
    ssrSettings_.stride = p.stride;
    ssrSettings_.thickness = p.thickness;
    ssrSettings_.maxDistance = p.maxDistance;
    ssrSettings_.edgeFade = p.edgeFade;
}

RasterRequest SsrFallbackTechnique::rasterRequest(const FrameRequest& frame) {
    RasterRequest r = frame.rasterRequest();
    r.readback = kGBufferSurfaceTargets;
    r.lighting = true;
    // The lit image is what SSR reads at its hits, so it is shadowed by the maps even when the
    // visible surfaces' own shadows are ray traced.
    r.lightingOptions.shadows = true;
    r.lightingOptions.walewskiBlend = tracerSettings_.blend == BlendRule::Walewski2019;
    r.shadowSettings = shadowSettings_;
    if (onDevice_) {
        // Nothing comes back: the ray-traced stage reads the targets on the device.
        r.readback = 0;
        r.lightingReadback = false;
    }
    if (ssrOn_) {
        ssr_->setSettings(ssrSettings_);
        r.passes = {ssr_.get()};
    }
    return r;
}

void SsrFallbackTechnique::prepare(SceneContext& context) {
    if (onDevice_) {
        deviceTracer_ = prepareDeviceGBufferRays(context, "device_ssr_fallback.rgen", "ssr_classify.comp", launch_);
        gbuffer_.prepareOnDevice(context.deviceRayScene(0.0));
        deviceComposite_ = std::make_unique<DeviceSeamComposite>(deviceTracer_->device());
        ssr_ = std::make_unique<SsrPass>(VulkanDevice::shared({.rayTracing = true}));
        ssr_->setReadback(false);
        renderOnDevice(context, RasterWarmUp::preparing(context.scene()));
        return;
    }
    const RayScene& rays = context.rayScene(0.0);
    if (!ssr_) ssr_ = std::make_unique<SsrPass>();
    RayStats unused;
    gbuffer_.render(context.rasterizer(), &rays, rasterRequest(RasterWarmUp::preparing(context.scene())), raster_, unused);
}

namespace {

// The ray-traced stage's output per texel, for the reflection composer and SSR's statistics.
struct TracedTexels {
    std::vector<ReflectiveTexel> texels;
    std::vector<glm::vec3> reflection;  // M: SSR's and the fallback's, weighted by SSR's confidence
    std::vector<ReflectionSource> source;
    std::vector<std::uint8_t> refractive;
    RayStats stats;
    std::uint64_t fallbackRays = 0, recursionRays = 0, pixelsTraced = 0;
};

static_assert(static_cast<int>(ReflectionSource::None) == sl::kReflectionNone && static_cast<int>(ReflectionSource::Ssr) == sl::kReflectionSsr &&
              static_cast<int>(ReflectionSource::RayTraced) == sl::kReflectionRayTraced &&
              static_cast<int>(ReflectionSource::Sky) == sl::kReflectionSky && static_cast<int>(ReflectionSource::Missing) == sl::kReflectionMissing);
static_assert(static_cast<int>(SsrFallbackTechnique::Fallback::RayTraced) == sl::kSsrFallbackRayTraced &&
              static_cast<int>(SsrFallbackTechnique::Fallback::Sky) == sl::kSsrFallbackSky &&
              static_cast<int>(SsrFallbackTechnique::Fallback::None) == sl::kSsrFallbackNone);

// What the stage's shared function (shaders/ssr_texel.h) asks of its backend besides the ray tree:
// SSR's outputs at texel i and the G-buffer at SSR's hit.
class SsrTexelBackend : public EmbreeTreeBackend {
public:
    SsrTexelBackend(const WhittedTracer& tracer, RayStats& stats, float coneSpread, const GBuffer& g, std::size_t i, const SsrPixel* ssr,
                    const Camera& camera, std::uint32_t* counts)
        : EmbreeTreeBackend(tracer, stats, coneSpread), g_(g), i_(i), ssr_(ssr), camera_(camera), counts_(counts) {}

    float ssrConfidence() const { return ssr_ && ssr_->resolved() ? ssr_->confidence : 0.0f; }
    glm::vec3 ssrHitColor() const { return ssr_->color; }
    glm::vec4 ssrHitOptical() const { return g_.optical[hitIndex()]; }
    glm::vec3 loadSsrHit() {
        hit_.emplace(g_, hitIndex(), camera_);
        return hit_->hit().position;
    }
    const SurfaceHit& ssrHitSurface() const { return hit_->hit(); }
    sl::SurfaceMaterial ssrHitMaterial() const { return surfaceMaterial(hit_->hit()); }
    glm::vec3 texelFacingNormal() const { return g_.facingNormal(i_); }
    void countSsrTexel(int kind) { ++counts_[kind]; }

private:
    std::size_t hitIndex() const { return g_.index(ssr_->hit.x, ssr_->hit.y); }

    const GBuffer& g_;
    std::size_t i_;
    const SsrPixel* ssr_;
    const Camera& camera_;
    std::uint32_t* counts_;
    std::optional<GBufferSurface> hit_;
};

// The ray-traced stage (de Macedo & Rodrigues §III): fallback rays where SSR failed, refractive
// texels, ray-traced shadows, and recursion past SSR hits that reflect or refract. Writes the
// texels it finishes (the sky, matte and refractive ones) into `image`.
TracedTexels traceTexels(const GBuffer& g, const Image& lit, const SsrResult* ssr, const WhittedTracer& tracer, const WhittedSettings& settings,
                         const sl::SsrTexelPolicy& policy, const Camera& camera, Image& image) {
    const std::size_t n = g.pixelCount();
    TracedTexels out{std::vector<ReflectiveTexel>(n), std::vector<glm::vec3>(n, glm::vec3(0.0f)),
                     std::vector<ReflectionSource>(n, ReflectionSource::None), std::vector<std::uint8_t>(n, 0), {}, 0, 0, 0};
    std::atomic<std::uint64_t> fallbackRays{0}, recursionRays{0}, pixelsTraced{0};
    const bool walewski = settings.blend == BlendRule::Walewski2019;
    out.stats = forEachPixelInParallel(image.width(), image.height(), [&](int x, int y, RayStats& st) {
        const std::size_t i = g.index(x, y);
        if (g.object(i) < 0 || !sl::ssrStageShades(g.optical[i], policy.rayTracedShadows)) {
            image.at(x, y) = lit.at(x, y);  // the sky, and opaque matte texels shaded by the maps
            return;
        }
        const GBufferSurface surface(g, i, camera);
        std::uint32_t counts[3] = {0, 0, 0};  // sl::kSsrCount*
        SsrTexelBackend backend(tracer, st, surface.footprint().spread, g, i, ssr ? &ssr->pixels[i] : nullptr, camera, counts);
        const sl::SsrTexelShading t =
            sl::shadeSsrTexel(backend, surface.hit(), EmbreeTreeBackend::surfaceMaterial(surface.hit()), g.optical[i], surface.incoming(),
                              backend.coneWidthAt(surface.footprint().width, 0.0f), kAmbientMedium, glm::vec3(lit.at(x, y)), policy);
        if (counts[sl::kSsrCountTraced]) ++pixelsTraced;
        if (counts[sl::kSsrCountFallback]) ++fallbackRays;
        if (counts[sl::kSsrCountRecursion]) ++recursionRays;
        out.refractive[i] = t.refractive;
        if (!t.composer) {
            image.at(x, y) = glm::vec4(sl::composedParts(t.parts, walewski), 1.0f);
            return;
        }
        out.reflection[i] = t.reflection;
        out.source[i] = static_cast<ReflectionSource>(t.source);
        out.texels[i] = {t.parts, true};
    });
    out.fallbackRays = fallbackRays.load();
    out.recursionRays = recursionRays.load();
    out.pixelsTraced = pixelsTraced.load();
    return out;
}

// The reflection composer: each reflective texel composed with its (seam-blurred) merged M.
// Returns the number of reflective texels and of those whose reflection is SSR's.
std::pair<std::size_t, std::size_t> composeReflections(TracedTexels& traced, BlendRule blend, Image& image) {
    std::size_t reflective = 0, ssrHits = 0;
    for (std::size_t i = 0; i < traced.texels.size(); ++i) {
        if (!traced.texels[i].composed) continue;
        ++reflective;
        ssrHits += traced.source[i] == ReflectionSource::Ssr;
        sl::HitParts& parts = traced.texels[i].parts;
        parts.reflected = traced.reflection[i];
        image.data()[i] = glm::vec4(sl::composedParts(parts, blend == BlendRule::Walewski2019), 1.0f);
    }
    return {reflective, ssrHits};
}

}  // namespace

FrameResult SsrFallbackTechnique::render(SceneContext& context, const FrameRequest& frame) {
    if (onDevice_) return renderOnDevice(context, frame);
    Rasterizer& rasterizer = context.rasterizer();
    warmUp_.atSizeOf(frame, [&](const FrameRequest& f) {
        RayStats unused;
        gbuffer_.render(rasterizer, &context.rayScene(f.time), rasterRequest(f), raster_, unused);
    });
    FrameResult result;
    StageClock clock(result);
    // With gbuffer = "rays" the G-buffer comes from primary rays (stage gbuffer.rays, after the BVH
    // update it needs) and is uploaded for the lighting and SSR passes. The SSR pass runs inside the
    // rasterizer's frame: its GPU time is its stage.
    const RayScene* primaryRays = gbuffer_.rays() ? &updateRayScene(context, frame.time, clock, result) : nullptr;
    RayStats primaryStats;
    const GBuffer& g = gbuffer_.render(rasterizer, primaryRays, rasterRequest(frame), raster_, primaryStats, &clock);
    lapRasterFrame(clock, raster_);

    const RayScene& rays = primaryRays ? *primaryRays : updateRayScene(context, frame.time, clock, result);
    result.image = Image(frame.width, frame.height);
    TracedTexels traced = traceTexels(g, raster_.lighting, ssrOn_ ? &ssr_->result() : nullptr, WhittedTracer(rays, tracerSettings_),
                                      tracerSettings_, texelPolicy(), frame.camera, result.image);
    clock.lap("trace");

    const std::size_t blurred = blurReflectionSeams(traced.reflection, traced.source, frame.width, frame.height, blurRadius_, blurRange_);
    clock.lap("blend.seam_blur");

    const auto [reflective, ssrHits] = composeReflections(traced, tracerSettings_.blend, result.image);
    clock.lap("blend");

    traced.stats += primaryStats;
    recordRayCounters(traced.stats, static_cast<double>(traced.pixelsTraced), result);
    recordRasterWork(raster_, result);
    result.counters["reflective_pixels"] = static_cast<double>(reflective);
    result.counters["ssr_hits"] = static_cast<double>(ssrHits);
    result.counters["ssr_hit_rate"] = reflective > 0 ? static_cast<double>(ssrHits) / static_cast<double>(reflective) : 0.0;
    result.counters["fallback_rays"] = static_cast<double>(traced.fallbackRays);
    result.counters["ssr_recursion_rays"] = static_cast<double>(traced.recursionRays);
    result.counters["seam_blurred_pixels"] = static_cast<double>(blurred);
    recordSsrStatistics(traced.source, traced.refractive, result);
    return result;
}

void SsrFallbackTechnique::recordSsrStatistics(const std::vector<ReflectionSource>& source, const std::vector<std::uint8_t>& refractive,
                                               FrameResult& result) const {
    const SsrResult* ssr = ssrOn_ ? &ssr_->result() : nullptr;
    const int width = result.image.width(), height = result.image.height();
    const std::size_t n = source.size();
    Image sourceImage(width, height), failures(width, height), confidence(width, height);
    std::map<std::uint32_t, std::size_t> failuresByReason;
    std::uint64_t marchSteps = 0, marched = 0;
    for (std::size_t i = 0; i < n; ++i) {
        sourceImage.data()[i] = sourceColor(source[i], refractive[i] != 0);
        if (!ssr) continue;
        const SsrPixel& sp = ssr->pixels[i];
        if (sp.traced()) {
            ++marched;
            marchSteps += static_cast<std::uint64_t>(sp.steps);
        }
        failures.data()[i] = failureColor(sp.flags);
        confidence.data()[i] = glm::vec4(glm::vec3(sp.confidence), 1.0f);
        for (std::uint32_t bit = kSsrOffScreen; bit <= kSsrMaxDistance; bit <<= 1)
            if (sp.flags & bit) ++failuresByReason[bit];
    }
    result.debugImages["reflection_source"] = std::move(sourceImage);
    if (ssr) {
        result.debugImages["ssr_failures"] = std::move(failures);
        result.debugImages["ssr_confidence"] = std::move(confidence);
    }

    // SSR's work: march steps in all and per texel marched (the reflective texels SSR traced).
    result.counters["ssr_march_steps"] = static_cast<double>(marchSteps);
    result.counters["ssr_steps_per_reflective_pixel"] = marched > 0 ? static_cast<double>(marchSteps) / static_cast<double>(marched) : 0.0;
    result.counters["ssr_fail_off_screen"] = static_cast<double>(failuresByReason[kSsrOffScreen]);
    result.counters["ssr_fail_behind"] = static_cast<double>(failuresByReason[kSsrBehind]);
    result.counters["ssr_fail_out_of_steps"] = static_cast<double>(failuresByReason[kSsrOutOfSteps]);
    result.counters["ssr_fail_back_face"] = static_cast<double>(failuresByReason[kSsrBackFace]);
    result.counters["ssr_fail_max_distance"] = static_cast<double>(failuresByReason[kSsrMaxDistance]);
}

sl::SsrTexelPolicy SsrFallbackTechnique::texelPolicy() const {
    return {rayTracedShadows_, ssrSettings_.refractive, static_cast<int>(fallback_), recursion_ == Recursion::RayTraced};
}

FrameResult SsrFallbackTechnique::renderOnDevice(SceneContext& context, const FrameRequest& frame) {
    Rasterizer& rasterizer = rayTracingDeviceRasterizer(context);
    warmUp_.atSizeOf(frame, [&](const FrameRequest& f) {
        RayStats unused;
        gbuffer_.renderOnDevice(rasterizer, rasterRequest(f), raster_, unused);
    });
    FrameResult result;
    StageClock clock(result);
    // The whole frame is one command buffer on the device, one submission and one wait, as the CPU
    // needs nothing between its stages: with gbuffer = "rays" the G-buffer from primary rays, the
    // rasterizer's passes with SSR, the ray-traced stage, seam blur and composite (their GPU times
    // the counters gpu_trace_ms and gpu_composite_ms), then the copies of what the host reads: the
    // image and the counters. The acceleration structures are updated first.
    // (Noticed on lavapipe: the first frame at a size with gbuffer = "rays" reports the trace's
    // time as overhead, its timestamps ~0 ms; the later frames, which the runner times, are right.)
    updateDeviceRayScene(context, frame.time, clock, result);
    RasterRequest request = rasterRequest(frame);
    deviceTracer_->setSsr(ssrOn_ ? ssr_->colorView() : VK_NULL_HANDLE, ssrOn_ ? ssr_->hitView() : VK_NULL_HANDLE);
    const std::uint32_t options = sl::packSsrOptions(texelPolicy(), ssrOn_);  // frame.rules.y
    const bool walewski = tracerSettings_.blend == BlendRule::Walewski2019;
    request.last = [&](VkCommandBuffer cb) {
        deviceTracer_->record(
            cb, rasterizer.targets(), tracerSettings_, options,
            [&](VkCommandBuffer after) {
                deviceComposite_->record(after, deviceTracer_->texels(), deviceTracer_->deviceImage(), frame.width, frame.height,
                                         blurRadius_, blurRange_, walewski);
            },
            "composite");
    };
    RayStats rays;
    gbuffer_.renderOnDevice(rasterizer, request, raster_, rays);
    const DeviceGBufferTrace traced = deviceTracer_->lastTrace();
    std::vector<StageTime> recordedWithIt = gbuffer_.deviceCastStages();
    for (const StageTime& s : deviceLaunchStages(traced.gpuStages)) recordedWithIt.push_back(s);
    lapRasterFrame(clock, raster_, recordedWithIt);
    readDeviceImage(deviceTracer_->image(), frame.width, frame.height, result.image);
    clock.lap("readback");

    const auto& counts = traced.techniqueCounts;
    rays += traced.rays;
    recordRayCounters(rays, counts[0], result);
    recordRasterWork(raster_, result);
    recordGpuStages(traced.gpuStages, result);
    recordDeviceLaunch("trace", traced.rays, traced.invocations, gpuStageMilliseconds(traced.gpuStages, "trace"), result);
    gbuffer_.recordDeviceCast(result);
    result.counters["reflective_pixels"] = counts[3];
    result.counters["ssr_hits"] = counts[4];
    result.counters["ssr_hit_rate"] = counts[3] > 0 ? static_cast<double>(counts[4]) / static_cast<double>(counts[3]) : 0.0;
    result.counters["fallback_rays"] = counts[1];
    result.counters["ssr_recursion_rays"] = counts[2];
    result.counters["seam_blurred_pixels"] = deviceComposite_->blurredTexels();

    // After the timed stages, in a submission of their own: SSR's outputs and the texels'
    // reflection sources, for SSR's statistics and the debug images.
    const VulkanDevice::Diagnostics diagnostics;
    const glm::vec4* records = deviceTracer_->readTexels([&](VkCommandBuffer cb) {
        if (ssrOn_) ssr_->recordReadback(cb);
    });
    if (ssrOn_) ssr_->unpack();
    const std::size_t n = static_cast<std::size_t>(frame.width) * frame.height;
    std::vector<ReflectionSource> source(n);
    std::vector<std::uint8_t> refractive(n);
    for (std::size_t i = 0; i < n; ++i) {
        source[i] = static_cast<ReflectionSource>(static_cast<int>(records[DeviceGBufferTracer::kTexelRecords * i].w));
        refractive[i] = records[DeviceGBufferTracer::kTexelRecords * i + 3].y != 0.0f;
    }
    recordSsrStatistics(source, refractive, result);
    return result;
}

}  // namespace hybridlab
