#pragma once
// Records every ray a RayScene traces (for benchmarks that replay the same rays with bare Embree
// calls). Thread-safe: each thread appends to its own list.
#include <cstdint>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include <glm/vec3.hpp>

namespace hybridlab {

struct LoggedRay {
    glm::vec3 origin;
    glm::vec3 direction;
    float tmin;
    float tmax;
    bool shadow;  // traced with rtcOccluded1 (else rtcIntersect1)
    // Rays traced as one coherent packet (RayScene::intersectCoherent) are logged together, lane
    // packetLane of packetSize; a ray traced alone is lane 0 of 1.
    std::uint8_t packetSize = 1;
    std::uint8_t packetLane = 0;
};

class RayLog {
public:
    void record(const LoggedRay& r) { perThread_.local().push_back(r); }

    // All rays, thread by thread.
    std::vector<LoggedRay> collect() const {
        std::vector<LoggedRay> all;
        for (const auto& v : perThread_) all.insert(all.end(), v.begin(), v.end());
        return all;
    }

private:
    tbb::enumerable_thread_specific<std::vector<LoggedRay>> perThread_;
};

}  // namespace hybridlab
