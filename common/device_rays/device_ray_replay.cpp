#include "common/device_rays/device_ray_replay.h"

#include <algorithm>

namespace hybridlab {

using namespace device_rays;

DeviceRayReplay::DeviceRayReplay(const DeviceRayScene& scene) : pipeline_(scene, "device_replay.rgen") {}

void DeviceRayReplay::setRays(const std::vector<LoggedRay>& rays) {
    // Radiance rays first, then shadow rays (device_replay.rgen).
    std::vector<DeviceRay> list;
    list.reserve(rays.size());
    for (bool shadow : {false, true}) {
        for (const LoggedRay& r : rays) {
            if (r.shadow != shadow) continue;
            list.push_back({glm::vec4(r.origin, r.tmin), glm::vec4(r.direction, r.tmax)});
        }
        (shadow ? shadowRays_ : radianceRays_) = static_cast<std::uint32_t>(list.size()) - (shadow ? radianceRays_ : 0u);
    }
    const VulkanDevice& dev = pipeline_.device();
    // Device-local, as the rays a frame traces are made on the device: the replay times tracing.
    if (list.empty()) list.push_back({});
    pipeline_.setReplayRays(GpuBuffer::withData(dev, list.data(), list.size() * sizeof(DeviceRay), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT));
}

ReplayResult DeviceRayReplay::trace() {
    DeviceFrame frame{};
    frame.size = glm::ivec4(static_cast<int>(radianceRays_), static_cast<int>(shadowRays_), 0, 0);
    pipeline_.setFrame(frame);
    const std::uint32_t rays = radianceRays_ + shadowRays_, width = std::min<std::uint32_t>(std::max(rays, 1u), 4096u);
    RayLaunch launch{width, (rays + width - 1) / width, "replay"};
    launch.readOutput = false;  // the replay writes no image
    const DeviceLaunchCounts counts = pipeline_.launch(launch);
    ReplayResult r;
    r.hits = static_cast<std::uint32_t>(counts.rays.primary + counts.rays.shadow);
    for (const GpuStageTime& s : pipeline_.gpuStages()) r.gpuMilliseconds += s.milliseconds;
    return r;
}

}  // namespace hybridlab
