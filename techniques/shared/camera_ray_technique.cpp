#include "techniques/shared/camera_ray_technique.h"

#include <atomic>
#include <stdexcept>
#include "techniques/shared/camera_ray_packet.h"
#include "techniques/shared/device_rays.h"
#include "techniques/shared/pixel_loop.h"
#include "techniques/shared/ray_counters.h"
#include "techniques/shared/ray_scene_update.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

ParameterBinder<CameraRayParameters> cameraRayParameters(double defaultImportanceCutoff) {
    ParameterBinder<CameraRayParameters> b;
    b.bind(&CameraRayParameters::recursion, recursionParameters(defaultImportanceCutoff));
    b.bind(&CameraRayParameters::supersample,
           ParamSpec::integer("supersample", 1, 1, 16, "n x n samples per pixel for display images (metrics use 1)"));
    b.bind(&CameraRayParameters::shading, tracedShadingParameters());
    b.bind(&CameraRayParameters::rays, rayBackendParameters());
    return b;
}

CameraRayTechnique::CameraRayTechnique(const CameraRayParameters& p, LensModelFactory lensModel)
    : settings_(p.tracerSettings()), supersample_(p.supersample), onDevice_(p.rays.onDevice), lensModelFactory_(std::move(lensModel)) {
    if (onDevice_ && lensModelFactory_) throw std::logic_error("a lens model traces on the CPU only");
}

void CameraRayTechnique::prepare(SceneContext& context) {
    if (onDevice_) {
        deviceTracer_ = prepareDeviceRays(context);
        return;
    }
    context.rayScene(0.0);
    if (lensModelFactory_) lensModel_ = lensModelFactory_(context.scene());
}

FrameResult CameraRayTechnique::render(SceneContext& context, const FrameRequest& frame) {
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
    // coherent packet, then each pixel's ray tree from its first hit.
    const RayStats total = n == 1 && !lensModel_ ? forEachPixelBlockInParallel(frame.width, frame.height, [&](const PixelBlock& block, RayStats& stats) {
        const CameraRayPacket packet(rays, cameraRays, block, frame.width, frame.height, stats);
        for (int k = 0; k < block.count; ++k)
            result.image.at(block.x[k], block.y[k]) = glm::vec4(tracer.radianceFrom(packet.rays[k], packet.hit(k), 0, 1.0f, stats, cone), 1.0f);
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

}  // namespace hybridlab
