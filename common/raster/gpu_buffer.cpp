#include "common/raster/gpu_buffer.h"

#include <cstring>

#include "common/raster/vulkan_error.h"

namespace hybridlab {

GpuBuffer::GpuBuffer(const VulkanDevice& device, VkDeviceSize size, VkBufferUsageFlags usage, Memory memory) : size_(size) {
    VkDevice d = device.device();
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = size > 0 ? size : 4;  // zero-sized buffers are not allowed; empty scenes still bind one
    bci.usage = usage;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer b;
    checkVk(vkCreateBuffer(d, &bci, nullptr, &b), "creating a buffer");
    buffer_ = UniqueBuffer(d, b);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(d, b, &req);
    memory_ = device.allocate(req, memory, "buffer", (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0, &properties_);
    checkVk(vkBindBufferMemory(d, b, memory_, 0), "binding buffer memory");
    if (memory != Memory::DeviceLocal) checkVk(vkMapMemory(d, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "mapping buffer memory");
}

GpuBuffer GpuBuffer::withData(const VulkanDevice& device, const void* data, VkDeviceSize size, VkBufferUsageFlags usage) {
    GpuBuffer b(device, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, Memory::DeviceLocal);
    b.upload(device, data, size);
    return b;
}

void GpuBuffer::upload(const VulkanDevice& device, const void* data, VkDeviceSize size, VkDeviceSize offset) {
    if (size == 0) return;
    GpuBuffer staging(device, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, Memory::HostVisible);
    staging.write(data, size);
    device.submitAndWait([&](VkCommandBuffer cb) {
        VkBufferCopy copy{0, offset, size};
        vkCmdCopyBuffer(cb, staging.buffer(), buffer_, 1, &copy);
    });
}

VkDeviceAddress GpuBuffer::deviceAddress(const VulkanDevice& device) const {
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = buffer_;
    return vkGetBufferDeviceAddress(device.device(), &info);
}

const void* GpuBuffer::readBack(VkDeviceSize bytes) const {
    VulkanDevice::countReadBack(bytes);
    return mapped_;
}

void GpuBuffer::write(const void* data, VkDeviceSize size, VkDeviceSize offset) {
    if (size > 0) std::memcpy(static_cast<char*>(mapped_) + offset, data, size);
}

}  // namespace hybridlab
