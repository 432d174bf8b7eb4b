#pragma once
// A Vulkan buffer with its own memory: device-local (filled through a staging copy) or host-visible
// and persistently mapped (per-frame uniforms, read-back).
#include <cstddef>

#include "common/raster/vk_unique.h"
#include "common/raster/vulkan_device.h"

namespace hybridlab {

class GpuBuffer {
public:
    using Memory = VulkanDevice::MemoryUse;

    GpuBuffer() = default;
    GpuBuffer(const VulkanDevice& device, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory);

    // A device-local buffer holding `data`, uploaded through a staging buffer.
    static GpuBuffer withData(const VulkanDevice& device, const void* data, VkDeviceSize size, VkBufferUsageFlags usage);

    VkBuffer buffer() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    bool valid() const { return static_cast<bool>(buffer_); }
    // Host-visible buffers only (coherent: no flush needed): where the host writes.
    void* mapped() const { return mapped_; }
    // Host-visible buffers the device wrote, after it finished: their first `bytes` (count
    // elements of T), counted as read back to the host (VulkanDevice::workSoFar()).
    const void* readBack(VkDeviceSize bytes) const;
    template <class T>
    const T* readBack(std::size_t count) const {
        return static_cast<const T*>(readBack(count * sizeof(T)));
    }
    // Buffers created with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT only.
    VkDeviceAddress deviceAddress(const VulkanDevice& device) const;
    void write(const void* data, VkDeviceSize size, VkDeviceSize offset = 0);

private:
    UniqueBuffer buffer_;
    UniqueDeviceMemory memory_;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;  // unmapped with the memory
};

}  // namespace hybridlab
