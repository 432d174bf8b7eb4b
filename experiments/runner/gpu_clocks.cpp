#include "experiments/runner/gpu_clocks.h"

#include <dlfcn.h>

#include <type_traits>

namespace hybridlab {

namespace {

// The few NVML entry points used, by their C signatures (nvml.h): NVML is found at run time, so
// the program builds and runs where the NVIDIA driver is not installed.
using NvmlDevice = void*;
constexpr int kNvmlSuccess = 0;
constexpr int kClockSm = 1, kClockMemory = 2;  // nvmlClockType_t
constexpr int kTemperatureGpu = 0;             // nvmlTemperatureSensors_t

struct Nvml {
    int (*init)() = nullptr;
    int (*deviceByIndex)(unsigned, NvmlDevice*) = nullptr;
    int (*clock)(NvmlDevice, int, unsigned*) = nullptr;
    int (*performanceState)(NvmlDevice, int*) = nullptr;
    int (*temperature)(NvmlDevice, int, unsigned*) = nullptr;
    NvmlDevice device = nullptr;

    static const Nvml* load() {
        static const std::optional<Nvml> nvml = [] () -> std::optional<Nvml> {
            void* lib = dlopen("libnvidia-ml.so.1", RTLD_NOW | RTLD_LOCAL);
            if (!lib) return std::nullopt;
            Nvml n;
            const auto bind = [lib](auto& fn, const char* name) { fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(lib, name)); return fn != nullptr; };
            if (!bind(n.init, "nvmlInit_v2") || !bind(n.deviceByIndex, "nvmlDeviceGetHandleByIndex_v2") ||
                !bind(n.clock, "nvmlDeviceGetClockInfo") || !bind(n.performanceState, "nvmlDeviceGetPerformanceState") ||
                !bind(n.temperature, "nvmlDeviceGetTemperature"))
                return std::nullopt;
            if (n.init() != kNvmlSuccess || n.deviceByIndex(0, &n.device) != kNvmlSuccess) return std::nullopt;
            return n;
        }();
        return nvml ? &*nvml : nullptr;
    }
};

nlohmann::json sampleJson(const GpuClockSample& s) {
    return {{"sm_mhz", s.smMhz}, {"memory_mhz", s.memoryMhz}, {"pstate", s.performanceState}, {"temperature_c", s.temperatureC}};
}

}  // namespace

std::optional<GpuClockSample> sampleGpuClocks() {
    const Nvml* nvml = Nvml::load();
    if (!nvml) return std::nullopt;
    GpuClockSample s;
    if (nvml->clock(nvml->device, kClockSm, &s.smMhz) != kNvmlSuccess || nvml->clock(nvml->device, kClockMemory, &s.memoryMhz) != kNvmlSuccess)
        return std::nullopt;
    if (nvml->performanceState(nvml->device, &s.performanceState) != kNvmlSuccess) s.performanceState = -1;
    if (nvml->temperature(nvml->device, kTemperatureGpu, &s.temperatureC) != kNvmlSuccess) s.temperatureC = 0;
    return s;
}

nlohmann::json gpuClocksJson(const GpuClockSample& start, const GpuClockSample& end) {
    const bool changed = start.smMhz != end.smMhz || start.memoryMhz != end.memoryMhz || start.performanceState != end.performanceState;
    return {{"start", sampleJson(start)}, {"end", sampleJson(end)}, {"changed", changed}};
}

}  // namespace hybridlab
