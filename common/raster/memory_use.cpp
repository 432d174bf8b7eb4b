#include "common/raster/memory_use.h"

namespace hybridlab {

namespace {

// The types among `typeBits` with all of `flags` and none of `without`, in the device's order,
// appended to `out` (each once).
void appendTypesWith(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t typeBits, VkMemoryPropertyFlags flags,
                     std::vector<std::uint32_t>& out, VkMemoryPropertyFlags without = 0) {
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        const VkMemoryPropertyFlags has = memory.memoryTypes[i].propertyFlags;
        if (!(typeBits & (1u << i)) || (has & flags) != flags || (has & without)) continue;
        bool listed = false;
        for (std::uint32_t t : out) listed |= t == i;
        if (!listed) out.push_back(i);
    }
}

}  // namespace

std::vector<std::uint32_t> memoryTypeCandidates(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t typeBits, MemoryUse use) {
    constexpr VkMemoryPropertyFlags coherent = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    std::vector<std::uint32_t> types;
    switch (use) {
    case MemoryUse::DeviceLocal:
        // Not host-visible first: the BAR heap is small and kept for what the host rewrites.
        appendTypesWith(memory, typeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, types, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
        appendTypesWith(memory, typeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, types);
        break;
    case MemoryUse::HostVisible:
        // Cached first: the host reads what the device wrote fast from it.
        appendTypesWith(memory, typeBits, coherent | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, types);
        appendTypesWith(memory, typeBits, coherent, types);
        break;
    case MemoryUse::DeviceLocalHostVisible:
        // Then system memory: uncached (write-combined) before cached, as the host only writes it.
        appendTypesWith(memory, typeBits, coherent | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, types);
        appendTypesWith(memory, typeBits, coherent, types, VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        appendTypesWith(memory, typeBits, coherent, types);
        break;
    }
    return types;
}

}  // namespace hybridlab
