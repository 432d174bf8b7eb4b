#include "techniques/whitted/whitted_technique.h"

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "techniques/stage_clock.h"

namespace hybridlab {

std::vector<ParamSpec> WhittedTechnique::parameterSpecs(double defaultImportanceCutoff) {
    return {
        ParamSpec::integer("max_depth", 10, 0, 64, "secondary bounces before the local colour is returned"),
        ParamSpec::real("importance_cutoff", defaultImportanceCutoff, 0.0, 1.0,
                        "do not trace secondary rays whose weight in the pixel is below this (0: full ray tree)"),
        ParamSpec::integer("supersample", 1, 1, 16, "n x n samples per pixel for display images (metrics use 1)"),
        ParamSpec::choice("blend", "design", {"design", "walewski2019"},
                          "composition rule: DESIGN.md's, or Walewski 2019 eqs. (5)-(6) averaged"),
        ParamSpec::boolean("shadows", true, "trace shadow rays (false: every light unshadowed, to compare with raster shadows off)"),
    };
}

TechniqueInfo WhittedTechnique::info() {
    return {"whitted",
            "Reference: full recursive Whitted ray tracing (Embree), hard shadows, reflection and refraction to depth 10",
            parameterSpecs(0.0), [](const ParameterSet& p) { return std::make_unique<WhittedTechnique>(p); }};
}

WhittedTechnique::WhittedTechnique(const ParameterSet& p) {
    settings_.maxDepth = static_cast<int>(p.getInt("max_depth"));
    settings_.importanceCutoff = static_cast<float>(p.getFloat("importance_cutoff"));
    settings_.blend = p.getChoice("blend") == "walewski2019" ? BlendRule::Walewski2019 : BlendRule::Design;
    settings_.shadows = p.getBool("shadows");
    supersample_ = static_cast<int>(p.getInt("supersample"));
}

void WhittedTechnique::prepare(SceneContext& context) { context.rayScene(0.0); }

FrameResult WhittedTechnique::render(SceneContext& context, const FrameRequest& frame) {
    FrameResult result;
    StageClock clock(result);
    const RayScene& rays = context.rayScene(frame.time);
    clock.lap("bvh_update");

    const WhittedTracer tracer(rays, settings_);
    result.image = Image(frame.width, frame.height);
    tbb::combinable<RayStats> statsPerThread;
    const int n = supersample_;
    const float aspect = frame.aspect();
    constexpr int kTile = 16;
    tbb::parallel_for(tbb::blocked_range2d<int>(0, frame.height, kTile, 0, frame.width, kTile), [&](const tbb::blocked_range2d<int>& r) {
        RayStats& stats = statsPerThread.local();
        for (int y = r.rows().begin(); y < r.rows().end(); ++y) {
            for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                glm::vec3 sum(0.0f);
                for (int sy = 0; sy < n; ++sy) {
                    for (int sx = 0; sx < n; ++sx) {
                        // Sub-pixel sample centres; n = 1 is the pixel centre.
                        glm::vec2 ndc((x + (sx + 0.5f) / n) / frame.width * 2.0f - 1.0f,
                                      (y + (sy + 0.5f) / n) / frame.height * 2.0f - 1.0f);
                        ++stats.primary;
                        sum += tracer.radiance(frame.camera.rayThroughNdc(ndc, aspect), 0, 1.0f, stats);
                    }
                }
                result.image.at(x, y) = glm::vec4(sum / static_cast<float>(n * n), 1.0f);
            }
        }
    });
    clock.lap("trace");

    RayStats total;
    statsPerThread.combine_each([&](const RayStats& s) { total += s; });
    result.counters["rays_primary"] = static_cast<double>(total.primary);
    result.counters["rays_shadow"] = static_cast<double>(total.shadow);
    result.counters["rays_reflection"] = static_cast<double>(total.reflection);
    result.counters["rays_refraction"] = static_cast<double>(total.refraction);
    result.counters["rays_total"] = static_cast<double>(total.total());
    result.counters["pixels_ray_traced"] = static_cast<double>(frame.width) * frame.height;
    return result;
}

}  // namespace hybridlab
