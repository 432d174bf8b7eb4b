#include "experiments/runner/device_record.h"

#include <sys/utsname.h>

#include <cstdlib>
#include <fstream>
#include <thread>

#include <embree3/rtcore.h>
#include <tbb/global_control.h>

#include "common/core/program_version.h"
#include "common/raster/vulkan_device.h"
#include "common/raster/vulkan_error.h"

namespace hybridlab {

namespace {

using nlohmann::json;

// The value of `key` in a "key: value" (/proc/cpuinfo) or key=value (/etc/os-release) file, unquoted.
std::string fileField(const char* file, const std::string& key, char separator) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        const auto at = line.find(separator);
        if (at == std::string::npos) continue;
        std::string k = line.substr(0, at), v = line.substr(at + 1);
        while (!k.empty() && (k.back() == ' ' || k.back() == '\t')) k.pop_back();
        if (k != key) continue;
        while (!v.empty() && v.front() == ' ') v.erase(v.begin());
        if (v.size() >= 2 && v.front() == '"' && v.back() == '"') v = v.substr(1, v.size() - 2);
        return v;
    }
    return "unknown";
}

std::string deviceTypeName(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete_gpu";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated_gpu";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual_gpu";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        default: return "other";
    }
}

std::string embreeVersion() {
    RTCDevice d = rtcNewDevice("verbose=0");
    if (!d) return std::string(RTC_VERSION_STRING) + " (headers; no device)";
    const auto v = rtcGetDeviceProperty(d, RTC_DEVICE_PROPERTY_VERSION);  // major * 10000 + minor * 100 + patch
    rtcReleaseDevice(d);
    return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
}

std::string text(const json& record, const char* key) {
    const json v = record.value(key, json());
    return v.is_string() ? v.get<std::string>() : v.is_null() ? "?" : v.dump();
}

}  // namespace

bool rendersOnCpu() {
    try {
        return VulkanDevice::shared()->type() == VK_PHYSICAL_DEVICE_TYPE_CPU;
    } catch (const VulkanUnavailable&) {
        return true;
    }
}

json deviceRecord() {
    json r;
    r["cpu_model"] = fileField("/proc/cpuinfo", "model name", ':');
    r["cpu_cores"] = std::thread::hardware_concurrency();
    try {
        const auto vk = VulkanDevice::shared();
        const std::uint32_t api = vk->properties().apiVersion;
        r["vulkan_device"] = vk->name();
        r["vulkan_device_type"] = deviceTypeName(vk->type());
        r["vulkan_driver"] = vk->driver();
        r["vulkan_api_version"] = std::to_string(VK_API_VERSION_MAJOR(api)) + "." + std::to_string(VK_API_VERSION_MINOR(api)) + "." +
                                  std::to_string(VK_API_VERSION_PATCH(api));
    } catch (const VulkanUnavailable& e) {
        r["vulkan_device"] = std::string("none: ") + e.what();
        r["vulkan_device_type"] = "none";
        r["vulkan_driver"] = "none";
        r["vulkan_api_version"] = "none";
    }
    r["embree_version"] = embreeVersion();
    r["tbb_threads"] = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    // Lavapipe's worker threads: LP_NUM_THREADS, or (unset) one per core.
    const char* lp = std::getenv("LP_NUM_THREADS");
    r["lp_num_threads"] = lp && *lp ? std::string(lp) : std::string("default");
    utsname u{};
    const std::string kernel = uname(&u) == 0 ? std::string(u.sysname) + " " + u.release + " " + u.machine : "unknown kernel";
    r["os"] = fileField("/etc/os-release", "PRETTY_NAME", '=') + ", " + kernel;
    r["program_version"] = programVersion();
    return r;
}

bool sameDevice(const json& a, const json& b) {
    if (a.is_null() || b.is_null()) return a.is_null() && b.is_null();
    json x = a, y = b;
    x.erase("program_version");
    y.erase("program_version");
    return x == y;
}

std::string deviceSummary(const json& r) {
    if (r.is_null()) return "unknown device (recorded before result sets named theirs)";
    return text(r, "vulkan_device") + " [" + text(r, "vulkan_device_type") + "; " + text(r, "vulkan_driver") + "; Vulkan " +
           text(r, "vulkan_api_version") + "], " + text(r, "cpu_model") + " x " + text(r, "cpu_cores") + " cores, Embree " +
           text(r, "embree_version") + ", TBB " + text(r, "tbb_threads") + " threads, LP_NUM_THREADS " + text(r, "lp_num_threads") + ", " +
           text(r, "os") + ", hybridlab " + text(r, "program_version");
}

}  // namespace hybridlab
