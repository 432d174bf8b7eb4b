#include "techniques/shared/device_rays.h"

#include <algorithm>

#include <glm/vec4.hpp>

#include "common/core/input_error.h"
#include "common/raster/vulkan_error.h"
#include "techniques/shared/ray_counters.h"

namespace hybridlab {

std::unique_ptr<DeviceWhittedTracer> prepareDeviceRays(SceneContext& context) {
    try {
        return std::make_unique<DeviceWhittedTracer>(context.deviceRayScene(0.0));
    } catch (const VulkanUnavailable& e) {
        throw InputError(std::string("rays = \"vulkan\": ") + e.what());
    }
}

std::unique_ptr<DeviceGBufferTracer> prepareDeviceGBufferRays(SceneContext& context, const std::string& raygenShader,
                                                              const std::string& classifyShader, const DeviceLaunchParameters& launch) {
    try {
        auto tracer = std::make_unique<DeviceGBufferTracer>(context.deviceRayScene(0.0), raygenShader, classifyShader);
        tracer->setCompactLaunch(launch.compact);
        rayTracingDeviceRasterizer(context);
        return tracer;
    } catch (const VulkanUnavailable& e) {
        throw InputError(std::string("rays = \"vulkan\": ") + e.what());
    }
}

Rasterizer& rayTracingDeviceRasterizer(SceneContext& context) { return context.rasterizer({.rayTracing = true}); }

void readDeviceImage(const GpuBuffer& pixels, int width, int height, Image& image) {
    image = Image(width, height);
    const auto* p = pixels.readBack<glm::vec4>(static_cast<std::size_t>(width) * height);
    std::copy(p, p + static_cast<std::size_t>(width) * height, image.data());
}

std::vector<StageTime> deviceLaunchStages(const std::vector<GpuStageTime>& stages) {
    std::vector<StageTime> parts;
    for (const GpuStageTime& g : stages) {
        const std::string name = g.name == "classify" ? "trace.classify" : g.name == "composite" ? "blend" : g.name;
        parts.push_back({name, g.milliseconds});
    }
    return parts;
}

void lapDeviceLaunch(StageClock& clock, const std::vector<GpuStageTime>& stages) { clock.lap(deviceLaunchStages(stages), "overhead"); }

void recordGpuStages(const std::vector<GpuStageTime>& stages, FrameResult& result) {
    for (const GpuStageTime& g : stages) result.counters["gpu_" + g.name + "_ms"] = g.milliseconds;
}

void recordDeviceLaunch(const std::string& kind, const RayStats& rays, const DeviceInvocations& invocations, double gpuMilliseconds,
                        FrameResult& result) {
    const double launched = static_cast<double>(invocations.launched), total = static_cast<double>(rays.total());
    result.counters[kind + "_invocations_launched"] = launched;
    result.counters[kind + "_invocations_traced"] = static_cast<double>(invocations.tracing);
    if (invocations.listed) result.counters[kind + "_texels_listed"] = static_cast<double>(*invocations.listed);
    result.counters[kind + "_rays_per_invocation"] = launched > 0.0 ? total / launched : 0.0;
    result.counters["gpu_" + kind + "_ns_per_ray"] = total > 0.0 ? 1e6 * gpuMilliseconds / total : 0.0;
}

double gpuStageMilliseconds(const std::vector<GpuStageTime>& stages, const std::string& stage) {
    double ms = 0.0;
    for (const GpuStageTime& g : stages)
        if (g.name == stage) ms += g.milliseconds;
    return ms;
}

const DeviceRayScene& updateDeviceRayScene(SceneContext& context, double time, StageClock& clock, FrameResult& result) {
    const DeviceRayScene& rays = context.deviceRayScene(time);
    clock.lap("bvh_update");
    result.counters["bvh_triangles"] = static_cast<double>(rays.triangleCount());
    result.counters["bvh_moving_triangles"] = static_cast<double>(rays.rigidMovingTriangles());
    result.counters["bvh_refit_triangles"] = static_cast<double>(rays.deformingTriangles());
    return rays;
}

void renderDeviceWhitted(DeviceWhittedTracer& tracer, const FrameRequest& frame, const WhittedSettings& settings, int supersample,
                         StageClock& clock, FrameResult& result) {
    const int n = supersample;
    const int width = frame.width * n;
    const DeviceTraceResult traced = tracer.launch(frame.camera, width, frame.height * n, settings);
    lapDeviceLaunch(clock, traced.gpuStages);
    // The image straight from the device's buffer, once: averaged where supersampled.
    if (n == 1) {
        readDeviceImage(tracer.output(), frame.width, frame.height, result.image);
    } else {
        const auto* pixels = tracer.output().readBack<glm::vec4>(static_cast<std::size_t>(width) * frame.height * n);
        result.image = Image(frame.width, frame.height);
        for (int y = 0; y < frame.height; ++y) {
            for (int x = 0; x < frame.width; ++x) {
                glm::vec4 sum(0.0f);
                for (int sy = 0; sy < n; ++sy)
                    for (int sx = 0; sx < n; ++sx) sum += pixels[static_cast<std::size_t>(y * n + sy) * width + x * n + sx];
                result.image.at(x, y) = glm::vec4(glm::vec3(sum) / static_cast<float>(n * n), 1.0f);
            }
        }
    }
    clock.lap("readback");
    recordRayCounters(traced.rays, static_cast<double>(frame.width) * frame.height, result);
    recordGpuStages(traced.gpuStages, result);
    recordDeviceLaunch("trace", traced.rays, traced.invocations, gpuStageMilliseconds(traced.gpuStages, "trace"), result);
}

}  // namespace hybridlab
