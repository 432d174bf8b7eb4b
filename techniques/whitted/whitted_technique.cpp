#include "techniques/whitted/whitted_technique.h"

#include <atomic>
#include <stdexcept>

#include "common/core/input_error.h"
#include "techniques/make_technique_info.h"
#include "techniques/shared/camera_ray_packet.h"
#include "techniques/shared/device_rays.h"
#include "techniques/shared/pixel_loop.h"
#include "techniques/shared/ray_counters.h"
#include "techniques/shared/ray_scene_update.h"
#include "techniques/shared/two_term_tracer.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

namespace {

struct WhittedParameters {
    CameraRayParameters camera;
    bool twoTermLenses{};  // lens_model = "two_term"
};

// Hakura & Snyder 2001 §6's uniformly sampled ray tracing restricted to the two-term model.
class TwoTermLenses : public LensPixelModel {
public:
    explicit TwoTermLenses(const Scene& scene) : tracer_(scene) {}
    glm::vec3 radiance(const WhittedTracer& tracer, const RayScene& rays, const Ray& ray, RayStats& stats, RayCone cone,
                       bool* lensPixel) const override {
        return tracer_.radiance(tracer, rays, ray, stats, cone, lensPixel);
    }

private:
    TwoTermTracer tracer_;  // its lens systems
};

}  // namespace

WhittedTechnique::WhittedTechnique(const CameraRayParameters& p, LensModelFactory lensModel)
    : settings_(p.tracerSettings()), supersample_(p.supersample), onDevice_(p.rays.onDevice), lensModelFactory_(std::move(lensModel)) {
    if (onDevice_ && lensModelFactory_) throw std::logic_error("a lens model traces on the CPU only");
}

void WhittedTechnique::prepare(SceneContext& context) {
    if (onDevice_) {
        deviceTracer_ = prepareDeviceRays(context);
        return;
    }
    context.rayScene(0.0);
    if (lensModelFactory_) lensModel_ = lensModelFactory_(context.scene());
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
    // With a lens model: the pixels it shaded and the rays spent on them (the paper's comparison).
    std::atomic<std::uint64_t> lensPixels{0}, lensRays{0};
    // One sample per pixel without a lens model: the camera rays of a block of pixels in one
    // coherent packet, and their first hits' shadow rays a packet per light, then each pixel's
    // ray tree from its first hit.
    const RayStats total = n == 1 && !lensModel_ ? forEachPixelBlockInParallel(frame.width, frame.height, [&](const PixelBlock& block, RayStats& stats) {
        const CameraRayPacket packet(rays, cameraRays, block, frame.width, frame.height, stats);
        FirstHitShadows shadows[CameraRayPacket::kSize];
        tracer.traceFirstHitShadows(packet.rays, packet.hits, packet.found, block.count, shadows);
        for (int k = 0; k < block.count; ++k)
            result.image.at(block.x[k], block.y[k]) =
                glm::vec4(tracer.radianceFrom(packet.rays[k], packet.hit(k), 0, 1.0f, stats, cone, kAmbientMedium, &shadows[k]), 1.0f);
    }) : forEachPixelInParallel(frame.width, frame.height, [&](int x, int y, RayStats& stats) {
        glm::vec3 sum(0.0f);
        const std::uint64_t raysBefore = stats.total();
        bool lens = false;
        for (int sy = 0; sy < n; ++sy) {
            for (int sx = 0; sx < n; ++sx) {
                // Sub-pixel sample centres; n = 1 is the pixel centre.
                glm::vec2 ndc((x + (sx + 0.5f) / n) / frame.width * 2.0f - 1.0f, (y + (sy + 0.5f) / n) / frame.height * 2.0f - 1.0f);
                ++stats.primary;
                const Ray ray = cameraRays.throughNdc(ndc);
                sum += lensModel_ ? lensModel_->radiance(tracer, rays, ray, stats, cone, &lens) : tracer.radiance(ray, 0, 1.0f, stats, cone);
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
    if (lensModel_) {
        result.counters["lens_pixels"] = static_cast<double>(lensPixels);
        result.counters["rays_lens_pixels"] = static_cast<double>(lensRays);
    }
    return result;
}


TechniqueInfo whittedTechniqueInfo() {
    ParameterBinder<WhittedParameters> parameters;
    parameters.bind(&WhittedParameters::camera, cameraRayParameters(/*defaultImportanceCutoff=*/0.0));
    parameters.bind(&WhittedParameters::twoTermLenses,
                    ParamSpec::choice("lens_model", "full", {"full", "two_term"},
                                      "pixels whose first hit is a lens object: the full ray tree, or the two-term greedy model "
                                      "(Hakura & Snyder 2001 §3: uniformly sampled ray tracing as layered_em approximates it)"),
                    {false, true});
    TechniqueInfo info = makeTechniqueInfo(
        "whitted", "Reference: full recursive Whitted ray tracing (Embree), hard shadows, reflection and refraction to depth 10",
        std::move(parameters),
        [](const WhittedParameters& p) {
            if (!p.twoTermLenses) return std::make_unique<WhittedTechnique>(p.camera);
            if (p.camera.rays.onDevice) throw InputError("lens_model = \"two_term\" traces on the CPU only; it needs rays = \"embree\"");
            return std::make_unique<WhittedTechnique>(p.camera, [](const Scene& scene) { return std::make_unique<TwoTermLenses>(scene); });
        },
        /*relativeCost=*/1.0);  // the unit
    // The ray tree's depth and importance cut-off: the reference's own speed for accuracy.
    using S = SearchDimension::Scale;
    info.searchSpace = {{"max_depth", {1LL, 2LL, 4LL, 8LL}, S::Linear}, {"importance_cutoff", {0.0, 0.02, 0.05, 0.1}, S::Linear}};
    return info;
}

}  // namespace hybridlab
