#pragma once
// The machine a result was measured on (DESIGN.md "Experiments and results"): processor, Vulkan
// device and driver, Embree, the thread counts in use, the OS and the program's version. Every
// result set's experiment.json holds it as "device"; `hybridlab --version` prints it; `hybridlab
// merge` compares the shards' records.
#include <string>

#include <nlohmann/json.hpp>

namespace hybridlab {

// This process's record: an object with cpu_model, cpu_cores, vulkan_device, vulkan_device_type,
// vulkan_driver, vulkan_api_version, embree_version, tbb_threads, lp_num_threads, os and
// program_version. Without a usable Vulkan device the Vulkan fields say "none" and why.
nlohmann::json deviceRecord();

// Whether this process renders on the CPU: its Vulkan device is a CPU (lavapipe) or there is none
// (Embree alone). The timing budget's clock depends on it (interleaved_timing.h).
bool rendersOnCpu();

// Whether two records describe the same measuring machine: equal in every field but the program
// version (a rebuilt program times the same machine). A record absent from an older result set is null.
bool sameDevice(const nlohmann::json& a, const nlohmann::json& b);

// One line for messages and table footers: "llvmpipe (LLVM 15.0.6, 256 bits) [cpu; llvmpipe, Mesa
// 25.0.7], Intel Xeon ... x 2 cores, Embree 3.13.5, TBB 2 threads, LP_NUM_THREADS default, Debian ...".
std::string deviceSummary(const nlohmann::json& record);

}  // namespace hybridlab
