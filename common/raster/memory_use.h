#pragma once
// Which memory type a buffer or image lives in, by what it is for. A GPU's memory types differ in
// where the bytes lie: device-local memory is the GPU's own, host-visible memory without the
// device-local bit is system memory that the GPU reads across PCIe, and the types with both (NVIDIA's
// and AMD's BAR, all of it with resizable BAR) are the GPU's own memory mapped for the host.
// lavapipe has one type with every bit, so the choice changes nothing there.
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace hybridlab {

enum class MemoryUse {
    // Written once through a staging copy (or by the device) and read by the device.
    DeviceLocal,
    // Written or read by the host (read-back, staging): coherent, cached where there is a cached type.
    HostVisible,
    // Rewritten by the host each frame and read by the device every frame (instances, per-frame
    // records): device-local and host-visible where the device has such a type, else system memory,
    // uncached first (the host only writes it).
    DeviceLocalHostVisible,
};

// The memory types among `typeBits` that suit `use`, best first; the caller takes the first whose
// allocation succeeds (a BAR heap without resizable BAR holds only 256 MiB). Empty: none suits.
std::vector<std::uint32_t> memoryTypeCandidates(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t typeBits, MemoryUse use);

}  // namespace hybridlab
