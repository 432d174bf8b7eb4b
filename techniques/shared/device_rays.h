#pragma once
// The rays of a technique with `rays = "vulkan"` (ray_backend_parameters.h): the ray-tracing Vulkan
// device's scene and tracers, shared by every technique that traces there.
#include <memory>
#include <string>
#include <vector>

#include "common/device_rays/device_gbuffer_tracer.h"
#include "common/device_rays/device_whitted_tracer.h"
#include "techniques/shared/device_launch_parameters.h"
#include "techniques/stage_clock.h"
#include "techniques/technique.h"

namespace hybridlab {

// Builds the device's ray scene and the Whitted pipeline in `prepare`. A device without ray
// tracing (a missing extension, say) is bad input for rays = "vulkan": InputError naming the
// device and what it lacks, before anything renders.
std::unique_ptr<DeviceWhittedTracer> prepareDeviceRays(SceneContext& context);
// The same for a hybrid whose ray stage reads the G-buffer on the device (`raygenShader` and its
// classification pass `classifyShader`, see device_gbuffer_tracer.h; launched as `launch` says):
// the tracer, and the scene's rasterizer on the ray-tracing device.
std::unique_ptr<DeviceGBufferTracer> prepareDeviceGBufferRays(SceneContext& context, const std::string& raygenShader,
                                                              const std::string& classifyShader, const DeviceLaunchParameters& launch);
// The rasterizer on the ray-tracing device, whose targets the G-buffer tracer reads.
Rasterizer& rayTracingDeviceRasterizer(SceneContext& context);

// The `bvh_update` stage on the device (DeviceRayScene::setTime), with the counters
// updateRayScene() reports for Embree's scene.
const DeviceRayScene& updateDeviceRayScene(SceneContext& context, double time, StageClock& clock, FrameResult& result);

// Whitted ray tracing of the frame on the device, n x n supersampled (the sub-pixel centres are
// the pixel centres of an n times larger image, averaged): the image, ray counters and the
// trace's GPU time (`gpu_trace_ms`).
// Copies the device's image (vec4 per texel, row-major) of a width x height frame into `image`.
void readDeviceImage(const GpuBuffer& pixels, int width, int height, Image& image);

// A device launch's GPU stages as the frame's stages: the classification as trace.classify, the
// trace, the pass after it as blend.
std::vector<StageTime> deviceLaunchStages(const std::vector<GpuStageTime>& stages);
// Ends a device launch's stage in `clock`: its GPU stages (deviceLaunchStages) and the rest of its
// wall clock, recording, submission and the wait, as overhead.
void lapDeviceLaunch(StageClock& clock, const std::vector<GpuStageTime>& stages);

// The GPU stages of a device launch as counters gpu_<stage>_ms.
void recordGpuStages(const std::vector<GpuStageTime>& stages, FrameResult& result);
// A device launch's work per invocation and per ray, as counters (`kind`: the launch's GPU stage,
// "trace" or "gbuffer.rays"): <kind>_invocations_launched, <kind>_invocations_traced (those that
// traced a ray), <kind>_texels_listed (a compacted launch's list), <kind>_rays_per_invocation
// (its rays over the launched invocations) and
// gpu_<kind>_ns_per_ray (the stage's GPU time over its rays), which compare launches of different
// sizes and selections where their times alone do not.
void recordDeviceLaunch(const std::string& kind, const RayStats& rays, const DeviceInvocations& invocations, double gpuMilliseconds,
                        FrameResult& result);
// The GPU time of `stage` among `stages` (0 when it did not run).
double gpuStageMilliseconds(const std::vector<GpuStageTime>& stages, const std::string& stage);

void renderDeviceWhitted(DeviceWhittedTracer& tracer, const FrameRequest& frame, const WhittedSettings& settings, int supersample,
                         StageClock& clock, FrameResult& result);

}  // namespace hybridlab
