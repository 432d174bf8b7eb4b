#include "techniques/layered_em/layered_em_technique.h"

#include <algorithm>

#include "common/core/io_error.h"
#include "common/core/log.h"
#include "techniques/layered_em/em_bake_command.h"
#include "techniques/layered_em/em_cache.h"
#include "techniques/layered_em/lens_draw.h"
#include "techniques/make_technique_info.h"
#include "techniques/shared/raster_stages.h"
#include "techniques/shared/raster_work_counters.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

// A lens system ready for per-frame tracing: its ray scenes and its welded mesh.
struct LayeredEmTechnique::System {
    LensSystem lens;
    LensMesh mesh;
    System(const Scene& scene, const LensSystemInfo& info) : lens(scene, info), mesh(buildLensMesh(lens)) {}
};

TechniqueInfo LayeredEmTechnique::info() {
    using P = LayeredEmParameters;
    const EmBakeSettings d;
    ParameterBinder<P> parameters;
    parameters.bind(&P::layers, ParamSpec::integer("layers", d.layers, 0, kMaxDrawnLayers,
                                                   "EM layers per lens system (0: automatic, the smallest under the distortion threshold)"));
    parameters.bind(&P::singleLayer,
                    ParamSpec::boolean("single_layer", false, "one EM layer per lens system (the classic single environment map; overrides layers)"));
    parameters.bind(&P::tau, ParamSpec::real("tau", d.tessellation.tauPixels, 0.5, 1000.0,
                                             "per-frame adaptive tessellation stops when projected edges are shorter (pixels, §5; the bake keeps its own)"));
    parameters.bind(&P::emSize, ParamSpec::integer("em_size", d.inference.size, 2, 1024, "cube-map texels a face side"));
    parameters.bind(&P::viewpointStep,
                    ParamSpec::real("viewpoint_step", d.viewpoints.stepDegrees, 0.5, 360.0, "degrees between viewpoint samples on the circle"));
    parameters.bind(&P::viewpoints, ParamSpec::integer("viewpoints", 0, 0, 100000, "keep only the first n viewpoint samples (0: the whole circle)"));
    parameters.bind(&P::bakeWidth, ParamSpec::integer("bake_width", d.width, 8, 4096, "lens image width of the bake (pixels)"));
    parameters.bind(&P::bakeHeight, ParamSpec::integer("bake_height", d.height, 8, 4096, "lens image height of the bake (pixels)"));
    parameters.bind(&P::supersampling, ParamSpec::integer("supersampling", d.records.supersampling, 1, 8, "n x n incoming rays a bake pixel"));
    parameters.bind(&P::confidenceAngle,
                    ParamSpec::real("confidence_angle", d.records.confidenceAngleDegrees, 0.0, 180.0,
                                    "theta_c of the bake's confidence image (degrees, §4.3; 0: the paper's 5 at 480 lines, scaled to the bake's height)"));
    parameters.bind(&P::neighbourViewpoints,
                    ParamSpec::integer("neighbour_viewpoints", d.neighbourViewpoints, 0, 16,
                                       "viewpoint samples on each side whose images each sample's EMs also match (§4.3)"));
    parameters.bind(&P::disocclusionPrevention,
                    ParamSpec::boolean("disocclusion_prevention", true,
                                       "ray continuation, neighbouring viewpoints and direct images in the bake (§4.1, §4.3)"));
    parameters.bind(&P::directImages,
                    ParamSpec::choice("direct_images", "auto", {"auto", "viewpoint", "origin"},
                                      "where the bake's direct images of the environment look from (§4.3): auto, the EM origin for a reflective "
                                      "lens system and the viewpoint for a refractive one, as the paper advises"),
                    {DirectImageSource::Automatic, DirectImageSource::Viewpoint, DirectImageSource::Origin});
    parameters.bind(&P::originImages,
                    ParamSpec::boolean("origin_images", d.originImages,
                                       "direct images also from the EM origin (six cube faces) for the texels no lens image of a sample's "
                                       "window reads: what the origin sees there, not empty"));
    parameters.bind(&P::viewpointBlending,
                    ParamSpec::boolean("viewpoint_blending", true, "blend the two nearest viewpoint samples (false: the nearest alone)"));
    parameters.bind(&P::emCache, ParamSpec::boolean("em_cache", true, "load and store baked EMs in the cache ($HYBRIDLAB_CACHE/layered-em)"));
    parameters.bind(&P::shadowMaps, shadowMapParameters());
    TechniqueInfo info = makeTechniqueInfo(
        "layered_em",
        "Hakura & Snyder 2001: layered inferred environment maps per lens system (baked), per-frame vertex ray tracing with "
        "adaptive tessellation, lens drawn with the EMs on the GPU",
        std::move(parameters), [](const P& p) { return std::make_unique<LayeredEmTechnique>(p); },
        /*relativeCost=*/0.3);  // a frame: vertex rays and one raster pass (the bake is per scene and cached)
    info.bakeCommand = emBakeCommand();
    return info;
}

EmBakeSettings LayeredEmTechnique::bakeSettings(const LayeredEmParameters& p) {
    EmBakeSettings s;
    s.layers = p.singleLayer ? 1 : p.layers;
    s.maxLayers = std::min(s.maxLayers, kMaxDrawnLayers);
    s.inference.size = p.emSize;
    s.viewpoints.stepDegrees = p.viewpointStep;
    s.viewpoints.maxSamples = p.viewpoints;
    s.width = p.bakeWidth;
    s.height = p.bakeHeight;
    s.records.supersampling = p.supersampling;
    s.records.confidenceAngleDegrees = p.confidenceAngle;
    s.neighbourViewpoints = p.neighbourViewpoints;
    s.originImages = p.originImages;
    s.directImageSource = p.directImages;
    if (!p.disocclusionPrevention) s.disablePrevention();
    return s;
}

LayeredEmTechnique::LayeredEmTechnique(const LayeredEmParameters& p) : bake_(bakeSettings(p)) {
    frameTessellation_ = bake_.tessellation;
    frameTessellation_.tauPixels = p.tau;
    blendViewpoints_ = p.viewpointBlending;
    useCache_ = p.emCache;
    shadowSettings_ = p.shadowMaps.settings();
}

LayeredEmTechnique::~LayeredEmTechnique() = default;

RasterRequest LayeredEmTechnique::rasterRequest(const FrameRequest& frame) {
    RasterRequest r = frame.rasterRequest();
    r.lighting = true;
    r.lightingOptions.shadows = true;
    r.lightingOptions.environmentMapping = true;
    r.shadowSettings = shadowSettings_;
    r.passes = {pass_.get()};
    return r;
}

namespace {

// The cache only saves a later bake, so a cache that cannot be written costs that and not the
// frame: one warning, and the caller renders without storing. False when `em` was not stored.
bool storeInCache(const std::filesystem::path& file, const LayeredEm& em) {
    try {
        writeLayeredEm(file, em);
        return true;
    } catch (const IoError& e) {
        warn(std::string("the layered-EM cache cannot be written (") + e.what() + "); rendering without storing the baked EMs");
        return false;
    }
}

}  // namespace

void LayeredEmTechnique::prepare(SceneContext& context) {
    const Scene& scene = context.scene();
    systems_.clear();
    ems_.clear();
    const std::filesystem::path dir = defaultLayeredEmCacheDir();
    bool storing = useCache_;
    for (const LensSystemInfo& info : findLensSystems(scene)) {
        systems_.push_back(std::make_unique<System>(scene, info));
        const std::filesystem::path file = dir / (layeredEmCacheKey(scene, info, bake_) + ".hlem");
        std::optional<LayeredEm> em;
        if (useCache_) em = findLayeredEm(file, scene, info, bake_);
        if (!em) {
            EmBakeStats stats;
            em = bakeLayeredEm(scene, info, bake_, stats);
            if (storing) storing = storeInCache(file, *em);
        }
        ems_.push_back(std::move(*em));
    }
    if (!pass_) pass_ = std::make_unique<LayeredEmPass>();
    pass_->forgetResidentTexels();  // ems_ was refilled
    context.rasterizer().render(rasterRequest(RasterWarmUp::preparing(scene)), raster_);
}

FrameResult LayeredEmTechnique::render(SceneContext& context, const FrameRequest& frame) {
    warmUp_.atSizeOf(frame, [&](const FrameRequest& f) { context.rasterizer().render(rasterRequest(f), raster_); });
    FrameResult result;
    StageClock clock(result);
    // §5 per frame: vertex ray tracing with adaptive tessellation, then texture coordinates.
    TessellationStats stats;
    std::uint64_t vertices = 0, triangles = 0;
    std::vector<LensDrawGeometry> geometry;
    std::vector<LensDraw> draws;
    geometry.reserve(systems_.size());
    for (std::size_t s = 0; s < systems_.size(); ++s) {
        const TessellatedLens lens = tessellateLens(systems_[s]->lens, systems_[s]->mesh, frame.camera, frame.width, frame.height, frameTessellation_);
        clock.lap({{"trace.lens_vertices", lens.stats.traceMilliseconds}}, "lens.tessellation");
        stats.pathQueries += lens.stats.pathQueries;
        stats.visibilityQueries += lens.stats.visibilityQueries;
        stats.tracedVertices += lens.stats.tracedVertices;
        vertices += lens.vertices.size();
        triangles += lens.triangles.size();
        geometry.push_back(lensDrawGeometry(lens, ems_[s].layers, context.scene(), frame.camera, frame.width, frame.height, bake_.inference.size));
        draws.push_back({&geometry.back(), &ems_[s], blendViewpoints(ems_[s], frame.camera.position, blendViewpoints_)});
        clock.lap("lens.texture_coordinates");
    }

    // The G-buffer, lighting and the lens pass in one frame, then the lens over the lit image.
    pass_->setDraws(std::move(draws));
    context.rasterizer().render(rasterRequest(frame), raster_);
    lapRasterFrame(clock, raster_);
    const Image& lens = pass_->result();
    result.image = std::move(raster_.lighting);
    std::size_t lensPixels = 0;
    for (int y = 0; y < frame.height; ++y) {
        for (int x = 0; x < frame.width; ++x) {
            glm::vec4& out = result.image.at(x, y);
            const glm::vec4& l = lens.at(x, y);
            if (l.a > 0.0f) {
                out = glm::vec4(glm::vec3(l), 1.0f);
                ++lensPixels;
            }
            out.a = 1.0f;
        }
    }
    clock.lap("blend");
    result.counters["rays_total"] = static_cast<double>(stats.pathQueries + stats.visibilityQueries);
    result.counters["rays_lens_paths"] = static_cast<double>(stats.pathQueries);
    result.counters["rays_visibility"] = static_cast<double>(stats.visibilityQueries);
    result.counters["vertices_traced"] = static_cast<double>(stats.tracedVertices);
    result.counters["vertices"] = static_cast<double>(vertices);
    result.counters["triangles"] = static_cast<double>(triangles);
    result.counters["lens_pixels"] = static_cast<double>(lensPixels);
    result.counters["pixels_ray_traced"] = 0.0;
    // The rasterizer's GPU passes (lens.draw is the lens pass) and its wall clock.
    for (const RasterStageTime& g : raster_.gpuStages) result.counters["gpu_" + g.name + "_ms"] = g.milliseconds;
    recordRasterWork(raster_, result);
    result.counters["raster_wall_ms"] = raster_.wallMilliseconds();
    result.debugImages["lens"] = lens;
    return result;
}

}  // namespace hybridlab
