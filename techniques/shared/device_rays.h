#pragma once
// Where a technique's rays run: `rays = "embree"` (the CPU, RayScene) or `rays = "vulkan"` (the
// ray-tracing Vulkan device, DeviceRayScene), declared once for every technique that traces.
#include <memory>

#include "common/device_rays/device_whitted_tracer.h"
#include "techniques/stage_clock.h"
#include "techniques/technique.h"

namespace hybridlab {

ParamSpec raysParameterSpec();
// True for rays = "vulkan" (false where the technique does not declare `rays`).
bool tracesOnDevice(const ParameterSet& params);

// Builds the device's ray scene and the Whitted pipeline in `prepare`. A device without ray
// tracing (a missing extension, say) is bad input for rays = "vulkan": InputError naming the
// device and what it lacks, before anything renders.
std::unique_ptr<DeviceWhittedTracer> prepareDeviceRays(SceneContext& context);

// The `bvh_update` stage on the device (DeviceRayScene::setTime), with the counters
// updateRayScene() reports for Embree's scene.
const DeviceRayScene& updateDeviceRayScene(SceneContext& context, double time, StageClock& clock, FrameResult& result);

// Whitted ray tracing of the frame on the device, n x n supersampled (the sub-pixel centres are
// the pixel centres of an n times larger image, averaged): the image, ray counters and the
// trace's GPU time (`gpu_trace_ms`).
void renderDeviceWhitted(DeviceWhittedTracer& tracer, const FrameRequest& frame, const WhittedSettings& settings, int supersample,
                         StageClock& clock, FrameResult& result);

}  // namespace hybridlab
