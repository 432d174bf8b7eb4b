#include "techniques/whitted/whitted_technique.h"

#include <atomic>

#include "techniques/layered_em/two_term_tracer.h"
#include "common/core/input_error.h"
#include "techniques/shared/device_rays.h"
#include "techniques/shared/depth_limit_parameter.h"
#include "techniques/shared/pixel_loop.h"
#include "techniques/shared/ray_counters.h"
#include "techniques/shared/ray_scene_update.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

std::vector<ParamSpec> WhittedTechnique::recursionParameterSpecs(double defaultImportanceCutoff) {
    return {
        ParamSpec::integer("max_depth", 10, 0, 64, "secondary bounces before the local colour is returned"),
        ParamSpec::real("importance_cutoff", defaultImportanceCutoff, 0.0, 1.0,
                        "do not trace secondary rays whose weight in the pixel is below this (0: full ray tree)"),
        ParamSpec::choice("blend", "design", {"design", "walewski2019"},
                          "composition rule: design = o_m*M + (1-o_m)*(o_r*R + (1-o_r)*C) (o_m reflectivity or Fresnel, "
                          "o_r 1-opacity), or walewski2019 = that averaged with the other order (Walewski 2019 eqs. (5)-(6))"),
        depthLimitParameterSpec(),
    };
}

std::vector<ParamSpec> WhittedTechnique::parameterSpecs(double defaultImportanceCutoff) {
    std::vector<ParamSpec> specs = recursionParameterSpecs(defaultImportanceCutoff);
    specs.push_back(ParamSpec::integer("supersample", 1, 1, 16, "n x n samples per pixel for display images (metrics use 1)"));
    specs.push_back(
        ParamSpec::boolean("shadows", true, "trace shadow rays (false: every light unshadowed, to compare with raster shadows off)"));
    specs.push_back(ParamSpec::choice("texture_filter", "cones", {"cones", "none"},
                                      "textures filtered over ray cones' footprints (as mip-mapping), or point lookups (as POV-Ray)"));
    return specs;
}

TechniqueInfo WhittedTechnique::info() {
    std::vector<ParamSpec> specs = parameterSpecs(0.0);
    specs.push_back(raysParameterSpec());
    specs.push_back(ParamSpec::choice("lens_model", "full", {"full", "two_term"},
                                      "pixels whose first hit is a lens object: the full ray tree, or the two-term greedy model "
                                      "(Hakura & Snyder 2001 §3: uniformly sampled ray tracing as layered_em approximates it)"));
    return {"whitted",
            "Reference: full recursive Whitted ray tracing (Embree), hard shadows, reflection and refraction to depth 10",
            std::move(specs), [](const ParameterSet& p) { return std::make_unique<WhittedTechnique>(p); },
            /*relativeCost=*/1.0};  // the unit
}

WhittedSettings WhittedTechnique::recursionSettings(const ParameterSet& p) {
    WhittedSettings s;
    s.maxDepth = static_cast<int>(p.getInt("max_depth"));
    s.importanceCutoff = static_cast<float>(p.getFloat("importance_cutoff"));
    s.blend = p.getChoice("blend") == "walewski2019" ? BlendRule::Walewski2019 : BlendRule::Design;
    s.depthLimit = depthLimitSetting(p);
    return s;
}

WhittedSettings WhittedTechnique::tracerSettings(const ParameterSet& p) {
    WhittedSettings s = recursionSettings(p);
    s.shadows = p.getBool("shadows");
    s.rayCones = p.getChoice("texture_filter") == "cones";
    return s;
}

WhittedTechnique::WhittedTechnique(const ParameterSet& p) : settings_(tracerSettings(p)) {
    supersample_ = static_cast<int>(p.getInt("supersample"));
    // rt_only shares this class without the parameter.
    twoTermLenses_ = p.values().count("lens_model") && p.getChoice("lens_model") == "two_term";
    onDevice_ = tracesOnDevice(p);
    if (onDevice_ && twoTermLenses_) throw InputError("lens_model = \"two_term\" traces on the CPU only; it needs rays = \"embree\"");
}

void WhittedTechnique::prepare(SceneContext& context) {
    if (onDevice_) {
        deviceTracer_ = prepareDeviceRays(context);
        return;
    }
    context.rayScene(0.0);
    if (twoTermLenses_) twoTerm_ = std::make_unique<TwoTermTracer>(context.scene());
}

FrameResult WhittedTechnique::render(SceneContext& context, const FrameRequest& frame) {
    FrameResult result;
    StageClock clock(result);
    if (deviceTracer_) {
        updateDeviceRayScene(context, frame.time, clock, result);
        renderDeviceWhitted(*deviceTracer_, frame, settings_, supersample_, clock, result);
        return result;
    }
    const RayScene& rays = updateRayScene(context, frame.time, clock, result);

    const WhittedTracer tracer(rays, settings_);
    result.image = Image(frame.width, frame.height);
    const int n = supersample_;
    const float aspect = frame.aspect();
    // A sub-pixel's cone when supersampled.
    const RayCone cone = pixelCone(frame.camera, frame.height * n);
    const CameraRays cameraRays(frame.camera, aspect);
    // Two-term mode: the pixels the model shaded and the rays spent on them (the paper's comparison).
    std::atomic<std::uint64_t> lensPixels{0}, lensRays{0};
    const RayStats total = forEachPixelInParallel(frame.width, frame.height, [&](int x, int y, RayStats& stats) {
        glm::vec3 sum(0.0f);
        const std::uint64_t raysBefore = stats.total();
        bool lens = false;
        for (int sy = 0; sy < n; ++sy) {
            for (int sx = 0; sx < n; ++sx) {
                // Sub-pixel sample centres; n = 1 is the pixel centre.
                glm::vec2 ndc((x + (sx + 0.5f) / n) / frame.width * 2.0f - 1.0f, (y + (sy + 0.5f) / n) / frame.height * 2.0f - 1.0f);
                ++stats.primary;
                const Ray ray = cameraRays.throughNdc(ndc);
                sum += twoTerm_ ? twoTerm_->radiance(tracer, rays, ray, stats, cone, &lens) : tracer.radiance(ray, 0, 1.0f, stats, cone);
            }
        }
        if (lens) {
            ++lensPixels;
            lensRays += stats.total() - raysBefore;
        }
        result.image.at(x, y) = glm::vec4(sum / static_cast<float>(n * n), 1.0f);
    });
    clock.lap("trace");
    recordRayCounters(total, static_cast<double>(frame.width) * frame.height, result);
    if (twoTerm_) {
        result.counters["lens_pixels"] = static_cast<double>(lensPixels);
        result.counters["rays_lens_pixels"] = static_cast<double>(lensRays);
    }
    return result;
}

}  // namespace hybridlab
