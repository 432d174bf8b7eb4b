#pragma once
// An NVIDIA GPU's clocks, performance state and temperature through NVML, loaded at run time
// (libnvidia-ml.so.1, which the driver installs): the runner samples them at the start and the end
// of each group's rounds and flags a group whose clocks moved. On a machine without NVML (no
// NVIDIA driver, lavapipe) there is no sample and nothing else changes.
#include <optional>

#include <nlohmann/json.hpp>

namespace hybridlab {

struct GpuClockSample {
    unsigned smMhz = 0, memoryMhz = 0;
    int performanceState = -1;  // P0 (fastest) .. P15; -1 unknown
    unsigned temperatureC = 0;
};

// The first NVIDIA device's, or none where NVML is absent or fails.
std::optional<GpuClockSample> sampleGpuClocks();

// {"start": {...}, "end": {...}, "changed": bool}: changed when the SM or memory clock or the
// performance state differs between the two samples.
nlohmann::json gpuClocksJson(const GpuClockSample& start, const GpuClockSample& end);

}  // namespace hybridlab
