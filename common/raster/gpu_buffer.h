#pragma once
// A Vulkan buffer with its own memory: device-local (filled through a staging copy), or host-visible
// and persistently mapped (read-back, staging), or device-local and mapped where the device has
// such memory (what the host rewrites each frame and the device reads: MemoryUse).
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
    // Copies `size` bytes of `data` to `offset` through a staging buffer, and waits: device-local
    // buffers created with VK_BUFFER_USAGE_TRANSFER_DST_BIT.
    void upload(const VulkanDevice& device, const void* data, VkDeviceSize size, VkDeviceSize offset = 0);

    VkBuffer buffer() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    bool valid() const { return static_cast<bool>(buffer_); }
    // The property flags of the memory type it lives in (VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, ...).
    VkMemoryPropertyFlags memoryProperties() const { return properties_; }
    // Host-visible and device-local-host-visible buffers only (coherent: no flush needed): where
    // the host writes.
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
    VkMemoryPropertyFlags properties_ = 0;
    void* mapped_ = nullptr;  // unmapped with the memory
};

}  // namespace hybridlab
