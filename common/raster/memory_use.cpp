#include "common/raster/memory_use.h"

namespace hybridlab {

namespace {

// The types among `typeBits` with all of `flags`, in the device's order, appended to `out` (each once).
void appendTypesWith(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t typeBits, VkMemoryPropertyFlags flags,
                     std::vector<std::uint32_t>& out) {
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i)) || (memory.memoryTypes[i].propertyFlags & flags) != flags) continue;
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
        for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
            if (!(memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT))
                appendTypesWith(memory, typeBits & (1u << i), VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, types);
        }
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
        for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
            if ((typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & coherent) == coherent &&
                !(memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_HOST_CACHED_BIT))
                appendTypesWith(memory, typeBits & (1u << i), coherent, types);
        }
        appendTypesWith(memory, typeBits, coherent, types);
        break;
    }
    return types;
}

}  // namespace hybridlab
