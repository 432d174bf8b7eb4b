#pragma once
// Replays a list of rays on the device, each traced alone (closest hit, or a shadow ray with the
// transparent-shadow any-hit), to measure the device's ray throughput on the very rays a frame
// traced (`hybridlab bench-rays`, against bare Embree on the same list).
#include <vector>

#include "common/device_rays/device_ray_pipeline.h"
#include "common/raytrace/ray_log.h"

namespace hybridlab {

struct ReplayResult {
    std::uint32_t hits = 0;        // radiance rays that hit, plus shadow rays stopped
    double gpuMilliseconds = 0.0;  // the launch, by GPU timestamps
};

class DeviceRayReplay {
public:
    explicit DeviceRayReplay(const DeviceRayScene& scene);

    // Uploads the rays to trace (radiance and shadow rays, in any order).
    void setRays(const std::vector<LoggedRay>& rays);
    ReplayResult trace();

private:
    DeviceRayPipeline pipeline_;
    std::uint32_t radianceRays_ = 0, shadowRays_ = 0;
};

}  // namespace hybridlab
