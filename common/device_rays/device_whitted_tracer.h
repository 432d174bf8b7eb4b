#pragma once
// Whitted ray tracing on a ray-tracing Vulkan device: WhittedTracer's algorithm on the device
// (held to its images by DeviceRays.WhittedAgreesWithEmbree*, tests/device_rays/test_device_rays.cpp), a
// ray-tracing pipeline (ray generation, radiance closest-hit and miss, shadow any-hit and miss;
// shaders/device_whitted.rgen and friends) over a DeviceRayScene. One invocation per pixel centre;
// rays counted by kind on the device; the trace timed with GPU timestamps.
#include <vector>

#include "common/device_rays/device_ray_pipeline.h"
#include "common/device_rays/device_ray_scene.h"
#include "common/image/image.h"
#include "common/raster/gpu_timer.h"
#include "common/raytrace/ray_stats.h"
#include "common/raytrace/whitted_tracer.h"
#include "common/scene/camera.h"

namespace hybridlab {

struct DeviceTraceResult {
    Image image;                          // linear radiance per pixel
    RayStats rays;                        // counted on the device
    DeviceInvocations invocations;
    std::vector<GpuStageTime> gpuStages;  // "trace"
};

// The launch's uniforms (device_ray_records.h DeviceFrame) for `camera` at width x height with
// `settings`, and `effects` traced at each camera ray's first hit.
device_rays::DeviceFrame deviceFrame(const DeviceRayScene& scene, const Camera& camera, int width, int height, const WhittedSettings& settings,
                                     TracedEffects effects = {});

class DeviceWhittedTracer {
public:
    explicit DeviceWhittedTracer(const DeviceRayScene& scene);

    // The image of `camera` at width x height through pixel centres, as WhittedTracer::radiance
    // from camera rays with `settings` (blend, depth limit, importance cut-off, shadows, ray
    // cones) and `effects` traced at each pixel's first hit.
    DeviceTraceResult trace(const Camera& camera, int width, int height, const WhittedSettings& settings, TracedEffects effects = {});
    // As trace(), leaving the image where the device wrote it (output()); result.image stays empty.
    DeviceTraceResult launch(const Camera& camera, int width, int height, const WhittedSettings& settings, TracedEffects effects = {});
    // After launch(): the image, vec4 per pixel, row-major, copied to the host.
    const GpuBuffer& output() const { return pipeline_.outputOnHost(); }

private:
    const DeviceRayScene& scene_;
    DeviceRayPipeline pipeline_;
};

}  // namespace hybridlab
