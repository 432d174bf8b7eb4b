#include "techniques/heuristic_rt/heuristic_rt_technique.h"

#include <algorithm>
#include <limits>

#include "common/core/input_error.h"
#include "common/raytrace/embree_tree_backend.h"
#include "techniques/heuristic_rt/heuristic.h"
#include "techniques/heuristic_rt/object_observations.h"
#include "techniques/heuristic_rt/selection_graph.h"
#include "techniques/heuristic_rt/shaders/heuristic_texel.h"
#include "techniques/make_technique_info.h"
#include "techniques/shared/device_rays.h"
#include "techniques/shared/gbuffer_surface.h"
#include "techniques/shared/pixel_loop.h"
#include "techniques/shared/raster_stages.h"
#include "techniques/shared/raster_warm_up.h"
#include "techniques/shared/raster_work_counters.h"
#include "techniques/shared/ray_counters.h"
#include "techniques/shared/ray_scene_update.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

namespace {

constexpr std::uint8_t effectBit(Effect e) { return static_cast<std::uint8_t>(1u << static_cast<int>(e)); }
constexpr std::uint8_t kAllEffects = effectBit(Effect::Shadows) | effectBit(Effect::Reflection) | effectBit(Effect::Refraction);

// The bits the shared per-texel shading reads (shaders/heuristic_texel.h).
static_assert(effectBit(Effect::Shadows) == shading_language::kSelectedShadows &&
              effectBit(Effect::Reflection) == shading_language::kSelectedReflection &&
              effectBit(Effect::Refraction) == shading_language::kSelectedRefraction);

}  // namespace

TechniqueInfo HeuristicRtTechnique::info() {
    using P = HeuristicRtParameters;
    ParameterBinder<P> parameters;
    parameters.bind(&P::budget, ParamSpec::real("budget", 0.0, 0.0, 1e18, "T: the cost budget of the selection (eq. 2 units, about rays); 0: unlimited"));
    parameters.bind(&P::targetMilliseconds, ParamSpec::real("target_ms", 0.0, 0.0, 1e6,
                                                            "frame-time target: T is set each frame from a learned cost-to-time rate (0: use `budget`)"));
    parameters.bind(&P::previousSelectionImportance,
                    ParamSpec::real("importance", 0.0, 0.0, 1e18, "I: relevance added to objects selected last frame (eq. 3)"));
    parameters.bind(&P::heuristic, ParamSpec::boolean("heuristic", true, "false: every visible object selected (the paper's \"no heuristic\" run)"));
    parameters.bind(&P::perEffect, ParamSpec::boolean("per_effect", false, "select shadows, reflections and refractions separately per object"));
    parameters.bind(&P::visiblePixelsByQueries,
                    ParamSpec::choice("visible_pixels", "ids", {"ids", "queries"},
                                      "A from the object-id target, or from precise occlusion queries (as the paper)"),
                    {false, true});
    parameters.bind(&P::unselectedShadows,
                    ParamSpec::choice("raster_shadows", "map", {"map", "off", "rays"},
                                      "shadows of pixels not ray traced: shadow maps, none (as the paper's P-buffer), or shadow rays "
                                      "(lighting = \"cpu\", where there are no shadow maps)"),
                    {P::UnselectedShadows::Map, P::UnselectedShadows::Off, P::UnselectedShadows::Rays});
    parameters.bind(&P::cpuLighting,
                    ParamSpec::choice("lighting", "raster", {"raster", "cpu"},
                                      "the P-buffer: the rasterizer's deferred lighting pass, or the same shading model on the CPU from the "
                                      "ray-cast G-buffer (gbuffer = \"rays\"): the whole frame on Embree, no rasterizer"),
                    {false, true});
    parameters.bind(&P::debugImages, ParamSpec::boolean("debug_images", true, "heuristic mask and the shadow, reflection and refraction images"));
    parameters.bind(&P::gbuffer, gbufferSourceParameters());
    parameters.bind(&P::rays, rayBackendParameters());
    parameters.bind(&P::launch, deviceLaunchParameters());
    // The tracer recurses and shades as the reference, cut off at rt_only's importance.
    parameters.bind(&P::recursion, recursionParameters(kTracedImportanceCutoff));
    parameters.bind(&P::shading, tracedShadingParameters());
    TechniqueInfo info = makeTechniqueInfo(
        "heuristic_rt",
        "Walewski 2019 / Sabino 2012: G-buffer, per-object heuristic and selection graph under a budget, secondary rays "
        "(Embree or the Vulkan device) for the selected objects' pixels, blending",
        std::move(parameters), [](const P& p) { return std::make_unique<HeuristicRtTechnique>(p); },
        /*relativeCost=*/0.4);  // 0.30-0.40 of the reference at 320x180 (whitted-classic, cornell-mirror-glass)
    // The budget T (eq. 2, about rays) per pixel in steps of sqrt(2) (Walewski 2019 Table 5's 1-3 M
    // at 1280x720 are 1.1-3.3; the quality need not grow with it monotonically: the selection
    // changes object by object), and the selected pixels' ray-tree cut-off.
    using S = SearchDimension::Scale;
    info.searchSpace = {{"budget", {0.125, 0.177, 0.25, 0.354, 0.5, 0.707, 1.0, 1.414, 2.0}, S::Log, /*perPixel=*/true},
                        {"importance_cutoff", {0.0, 0.02, 0.05, 0.1}, S::Linear}};
    return info;
}

HeuristicRtTechnique::HeuristicRtTechnique(const HeuristicRtParameters& p)
    : tracer_(p.recursion.settings()),
      budget_(p.budget),
      previousSelectionImportance_(p.previousSelectionImportance),
      heuristic_(p.heuristic),
      perEffect_(p.perEffect),
      visiblePixelsByQueries_(p.visiblePixelsByQueries),
      rasterShadows_(p.unselectedShadows == HeuristicRtParameters::UnselectedShadows::Map),
      unselectedShadowRays_(p.unselectedShadows == HeuristicRtParameters::UnselectedShadows::Rays),
      cpuLighting_(p.cpuLighting),
      debugImages_(p.debugImages),
      onDevice_(p.rays.onDevice),
      launch_(p.launch),
      gbuffer_(p.gbuffer) {
    p.shading.applyTo(tracer_);
    if (gbuffer_.rays() && visiblePixelsByQueries_)
        throw InputError("heuristic_rt: visible_pixels = \"queries\" needs the rasterizer's G-buffer (gbuffer = \"raster\"); "
                         "with gbuffer = \"rays\" the visible pixels come from the object ids");
    if (cpuLighting_ && !gbuffer_.rays())
        throw InputError("heuristic_rt: lighting = \"cpu\" lights the ray-cast G-buffer (gbuffer = \"rays\"); "
                         "the rasterizer's G-buffer is lit where it lies (lighting = \"raster\")");
    if (cpuLighting_ && onDevice_)
        throw InputError("heuristic_rt: lighting = \"cpu\" lights Embree's ray-cast G-buffer on the host; it needs rays = \"embree\"");
    if (cpuLighting_ && rasterShadows_)
        throw InputError("heuristic_rt: lighting = \"cpu\" draws no shadow maps; raster_shadows = \"rays\" (shadow rays) or \"off\"");
    if (!cpuLighting_ && unselectedShadowRays_)
        throw InputError("heuristic_rt: raster_shadows = \"rays\" needs lighting = \"cpu\"; the rasterizer's lighting pass "
                         "takes \"map\" or \"off\"");
    if (p.targetMilliseconds > 0.0) frameTimeBudget_.emplace(p.targetMilliseconds);
}

void HeuristicRtTechnique::prepare(SceneContext& context) {
    // Object-space bounds once per scene: finding them scans every vertex.
    const Scene& scene = context.scene();
    localBounds_.clear();
    for (std::size_t o = 0; o < scene.objects.size(); ++o) localBounds_.push_back(scene.objectLocalBounds(o));
    // Lavapipe compiles shaders at the first draw (and the ray-tracing pipeline at its creation).
    const FrameRequest warmUp = RasterWarmUp::preparing(scene);
    if (onDevice_) {
        deviceTracer_ = prepareDeviceGBufferRays(context, "device_heuristic_rt.rgen", "heuristic_classify.comp", launch_);
        gbuffer_.prepareOnDevice(context.deviceRayScene(0.0));
        pixelCounts_ = std::make_unique<ObjectPixelCountPass>(VulkanDevice::shared({.rayTracing = true}), scene.objects.size());
        renderOnDevice(context, warmUp);
        selectedLastFrame_.clear();
        if (frameTimeBudget_) frameTimeBudget_.emplace(frameTimeBudget_->targetMilliseconds());
        return;
    }
    context.rayScene(0.0);
    if (cpuLighting_) return;  // no rasterizer
    RasterRequest request = warmUp.rasterRequest();
    request.lightingOptions = {rasterShadows_, true, tracer_.blend == BlendRule::Walewski2019};
    context.rasterizer().render(request, raster_);
}

RasterRequest HeuristicRtTechnique::rasterRequest(const FrameRequest& frame) const {
    RasterRequest request = frame.rasterRequest();
    request.readback = onDevice_ ? 0 : kGBufferSurfaceTargets;
    request.lighting = true;
    request.lightingReadback = !onDevice_;
    request.lightingOptions = {rasterShadows_, true, tracer_.blend == BlendRule::Walewski2019};
    request.occlusionQueries = visiblePixelsByQueries_;
    if (onDevice_ && !visiblePixelsByQueries_) request.passes = {pixelCounts_.get()};
    return request;
}

HeuristicRtTechnique::Selection HeuristicRtTechnique::selectObjects(const Scene& scene, const FrameRequest& frame,
                                                                    const std::vector<std::uint64_t>& visiblePixels) {
    const std::vector<ObjectObservation> observations =
        observeVisibleObjects(scene, localBounds_, frame.time, frame.camera, frame.aspect(), visiblePixels, selectedLastFrame_);
    const int lights = static_cast<int>(scene.lights.size());
    Selection s;
    s.effectsByObject.assign(scene.objects.size(), 0);
    s.objectsVisible = observations.size();

    // Graph nodes: one per object, or per object and effect (its own cost term, the object's relevance).
    std::vector<SelectionNode> nodes;
    for (const ObjectObservation& o : observations) {
        const ObjectScore score = scoreObject(o, lights, previousSelectionImportance_);
        s.costVisible += score.C;
        if (!perEffect_) {
            nodes.push_back({o.object * kEffectCount, score.C, score.R});
            continue;
        }
        for (Effect e : {Effect::Shadows, Effect::Reflection, Effect::Refraction}) {
            if ((e == Effect::Reflection && !o.reflective) || (e == Effect::Refraction && !o.refractive)) continue;
            nodes.push_back({o.object * kEffectCount + static_cast<std::uint32_t>(e),
                             o.visiblePixels * raysPerPixel(e, lights) * o.estimatedCost, score.R});
        }
    }
    std::vector<std::uint32_t> chosen;
    if (heuristic_) {
        s.budget = frameTimeBudget_ ? frameTimeBudget_->budget() : budget_ > 0.0 ? budget_ : std::numeric_limits<double>::infinity();
        SelectionResult r = SelectionGraph(nodes).select(s.budget);
        chosen = std::move(r.selected);
        s.costSelected = r.costUsed;
    } else {
        s.budget = std::numeric_limits<double>::infinity();
        for (const SelectionNode& n : nodes) {
            chosen.push_back(n.object);
            s.costSelected += n.cost;
        }
    }
    for (std::uint32_t id : chosen) {
        const std::uint32_t object = id / kEffectCount;
        s.effectsByObject[object] |= perEffect_ ? effectBit(static_cast<Effect>(id % kEffectCount)) : kAllEffects;
    }
    selectedLastFrame_.assign(scene.objects.size(), false);
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        selectedLastFrame_[o] = s.effectsByObject[o] != 0;
        s.objectsSelected += selectedLastFrame_[o];
    }
    return s;
}

FrameResult HeuristicRtTechnique::render(SceneContext& context, const FrameRequest& frame) {
    if (onDevice_) return renderOnDevice(context, frame);
    const Scene& scene = context.scene();
    FrameResult result;
    StageClock clock(result);

    // The G-buffer and the P-buffer; with gbuffer = "rays" the G-buffer from primary rays
    // (stage gbuffer.rays, after the BVH update it needs); with lighting = "cpu" the P-buffer
    // after the selection, for the pixels not traced only.
    const RasterRequest request = rasterRequest(frame);
    const RayScene* primaryRays = gbuffer_.rays() ? &updateRayScene(context, frame.time, clock, result) : nullptr;
    RayStats primaryStats;
    const GBuffer& g = cpuLighting_ ? gbuffer_.cast(*primaryRays, request, kGBufferSurfaceTargets, primaryStats, &clock)
                                    : gbuffer_.render(context.rasterizer(), primaryRays, request, raster_, primaryStats, &clock);
    if (!cpuLighting_) lapRasterFrame(clock, raster_);

    // heuristic: the selection, then the heuristic mask.
    const Selection selection = selectObjects(
        scene, frame, visiblePixelsByQueries_ ? raster_.visiblePixelsByQuery : visiblePixelsFromIds(g, scene.objects.size()));
    const std::size_t pixels = g.pixelCount();
    pixelEffects_.assign(pixels, 0);
    std::size_t masked = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        const std::int64_t o = g.object(i);
        if (o < 0) continue;
        pixelEffects_[i] = selection.effectsByObject[static_cast<std::size_t>(o)];
        masked += pixelEffects_[i] != 0;
    }
    clock.lap("heuristic");

    const RayScene& rays = primaryRays ? *primaryRays : updateRayScene(context, frame.time, clock, result);

    RayStats stats;
    if (cpuLighting_) {
        stats += lightUnmaskedPixels(rays, g, frame, raster_.lighting);
        clock.lap("lighting.cpu");
    }

    // trace: Listings 8a-8d from the G-buffer, for masked pixels only.
    // The texel's terms by the one source the device's raygen shader runs (shaders/heuristic_texel.h).
    const WhittedTracer tracer(rays, tracer_);
    parts_.resize(pixels);
    const Image& lighting = raster_.lighting;
    stats += forEachPixelInParallel(frame.width, frame.height, [&](int x, int y, RayStats& st) {
        const std::size_t i = g.index(x, y);
        if (pixelEffects_[i] == 0) return;
        const GBufferSurface surface(g, i, frame.camera);
        EmbreeTreeBackend backend(tracer, st, surface.footprint().spread);
        parts_[i] = shading_language::heuristicTexelParts(backend, surface.hit(), EmbreeTreeBackend::surfaceMaterial(surface.hit()),
                                                          surface.incoming(), backend.coneWidthAt(surface.footprint().width, 0.0f),
                                                          kAmbientMedium, pixelEffects_[i], !cpuLighting_, unselectedShadowRays_,
                                                          glm::vec3(lighting.at(x, y)));
    });
    clock.lap("trace");

    // blend: Listing 10 (eqs. 4-6), or the shading model's composition, over the P-buffer (moved: the next frame's
    // read-back reallocates it).
    result.image = std::move(raster_.lighting);
    const bool walewski = tracer_.blend == BlendRule::Walewski2019;
    for (std::size_t i = 0; i < pixels; ++i) {
        if (pixelEffects_[i] != 0) result.image.data()[i] = glm::vec4(shading_language::composedParts(parts_[i], walewski), 1.0f);
    }
    clock.lap("blend");

    stats += primaryStats;
    recordFrame(selection, stats, masked, result);

    if (debugImages_) {
        Image mask(frame.width, frame.height), shadows(frame.width, frame.height), reflections(frame.width, frame.height),
            refractions(frame.width, frame.height);
        for (std::size_t i = 0; i < pixels; ++i) {
            mask.data()[i] = glm::vec4(glm::vec3(shading_language::selectedTracedEffects(pixelEffects_[i])), 1.0f);
            if (pixelEffects_[i] == 0) continue;
            shadows.data()[i] = glm::vec4(parts_[i].local, 1.0f);
            reflections.data()[i] = glm::vec4(parts_[i].reflected, 1.0f);
            refractions.data()[i] = glm::vec4(parts_[i].refracted, 1.0f);
        }
        result.debugImages["heuristic_mask"] = std::move(mask);
        result.debugImages["shadows"] = std::move(shadows);
        result.debugImages["reflections"] = std::move(reflections);
        result.debugImages["refractions"] = std::move(refractions);
    }
    return result;
}

RayStats HeuristicRtTechnique::lightUnmaskedPixels(const RayScene& rays, const GBuffer& g, const FrameRequest& frame, Image& pbuffer) const {
    // deferred_lighting.frag's P-buffer by the C++ shading model it computes again (RasterLighting
    // holds the two equal): the local colour, environment-mapped reflection and refraction (the
    // tracer's terms for effects not traced), the sky where nothing was hit; shadows by shadow rays
    // in place of the maps, or none. At least one bounce, so that max_depth = 0 keeps the sky terms
    // as the rasterizer's pass does (no ray is traced for them).
    WhittedSettings settings = tracer_;
    settings.maxDepth = std::max(settings.maxDepth, 1);
    const WhittedTracer tracer(rays, settings);
    const Scene& scene = rays.scene();
    const float aspect = frame.aspect();
    if (pbuffer.width() != frame.width || pbuffer.height() != frame.height) pbuffer = Image(frame.width, frame.height);
    return forEachPixelInParallel(frame.width, frame.height, [&](int x, int y, RayStats& st) {
        const std::size_t i = g.index(x, y);
        if (pixelEffects_[i] != 0) return;  // traced
        if (g.object(i) < 0) {
            pbuffer.at(x, y) = glm::vec4(skyRadiance(scene, frame.camera.rayThroughNdc(pixelCenterNdc(x, y, frame.width, frame.height), aspect).direction), 1.0f);
            return;
        }
        const GBufferSurface surface(g, i, frame.camera);
        const shading_language::HitParts p = tracer.shadeParts(surface.hit(), surface.incoming(), 0, 1.0f, st,
                                                               {unselectedShadowRays_, false, false}, surface.footprint());
        pbuffer.at(x, y) = glm::vec4(shading_language::composedParts(p, tracer_.blend == BlendRule::Walewski2019), 1.0f);
    });
}

void HeuristicRtTechnique::recordFrame(const Selection& selection, const RayStats& stats, std::size_t masked, FrameResult& result) {
    double rayTracingMs = 0.0, otherMs = 0.0;
    for (const StageTime& s : result.stages) (s.name == "trace" ? rayTracingMs : otherMs) += s.milliseconds;
    if (frameTimeBudget_) {
        result.counters["target_ms"] = frameTimeBudget_->targetMilliseconds();
        result.counters["predicted_ms"] = frameTimeBudget_->predictedMilliseconds(selection.costSelected);
        frameTimeBudget_->observe(selection.costSelected, rayTracingMs, otherMs);
    }
    recordRayCounters(stats, static_cast<double>(masked), result);
    recordRasterWork(raster_, result);
    result.counters["objects_visible"] = static_cast<double>(selection.objectsVisible);
    result.counters["objects_selected"] = static_cast<double>(selection.objectsSelected);
    result.counters["cost_visible"] = selection.costVisible;
    result.counters["cost_selected"] = selection.costSelected;
    if (selection.budget < std::numeric_limits<double>::infinity()) result.counters["budget"] = selection.budget;
}

FrameResult HeuristicRtTechnique::renderOnDevice(SceneContext& context, const FrameRequest& frame) {
    FrameResult result;
    StageClock clock(result);
    // The G-buffer, the P-buffer and the visible pixels per object, on the ray-tracing device; only
    // the counts come back. With gbuffer = "rays" the G-buffer from primary rays there (stage
    // gbuffer.rays, after the acceleration structures' update it needs), in the same submission.
    Rasterizer& rasterizer = rayTracingDeviceRasterizer(context);
    if (gbuffer_.rays()) updateDeviceRayScene(context, frame.time, clock, result);
    RayStats rays;
    gbuffer_.renderOnDevice(rasterizer, rasterRequest(frame), raster_, rays);
    lapRasterFrame(clock, raster_, gbuffer_.deviceCastStages());

    // heuristic: the selection, sent down as the effect bits of each object (the shader makes the
    // mask). It runs on the CPU between the rasterization and the ray tracing (Walewski 2019 §1 and
    // §3.2: the visible pixels A come from the rasterization stage, the selection goes to the GPU),
    // so the frame waits here for the counts: its one submission besides the trace's.
    const Selection selection = selectObjects(context.scene(), frame,
                                              visiblePixelsByQueries_ ? raster_.visiblePixelsByQuery : pixelCounts_->counts());
    deviceTracer_->setObjectData(std::vector<std::uint32_t>(selection.effectsByObject.begin(), selection.effectsByObject.end()));
    clock.lap("heuristic");

    if (!gbuffer_.rays()) updateDeviceRayScene(context, frame.time, clock, result);

    // Trace and blend: one launch over the G-buffer where it lies (the blend is its last line);
    // then the image comes back.
    const DeviceGBufferTrace traced = deviceTracer_->trace(rasterizer.targets(), tracer_, debugImages_ ? 1u : 0u);
    lapDeviceLaunch(clock, traced.gpuStages);
    readDeviceImage(deviceTracer_->image(), frame.width, frame.height, result.image);
    clock.lap("readback");

    rays += traced.rays;
    recordFrame(selection, rays, traced.techniqueCounts[0], result);
    recordGpuStages(traced.gpuStages, result);
    recordDeviceLaunch("trace", traced.rays, traced.invocations, gpuStageMilliseconds(traced.gpuStages, "trace"), result);
    gbuffer_.recordDeviceCast(result);
    if (debugImages_) {
        // The shader's per-texel records: the mask, then C, M and R (zero where not traced).
        const glm::vec4* records = deviceTracer_->readTexels();
        const char* names[DeviceGBufferTracer::kTexelRecords] = {"heuristic_mask", "shadows", "reflections", "refractions"};
        for (std::uint32_t k = 0; k < DeviceGBufferTracer::kTexelRecords; ++k) {
            Image image(frame.width, frame.height);
            for (std::size_t i = 0; i < image.pixelCount(); ++i) image.data()[i] = records[DeviceGBufferTracer::kTexelRecords * i + k];
            result.debugImages[names[k]] = std::move(image);
        }
    }
    return result;
}

}  // namespace hybridlab
