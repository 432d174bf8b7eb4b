#pragma once
// RAII for Vulkan handles owned by a device: one small move-only owner per handle type, destroyed
// with the device's destroy function (DESIGN.md "Conventions": RAII for every Vulkan handle).
#include <utility>

#include <vulkan/vulkan.h>

namespace hybridlab {

template <typename Handle, void (*Destroy)(VkDevice, Handle, const VkAllocationCallbacks*)>
class DeviceObject {
public:
    DeviceObject() = default;
    DeviceObject(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
    ~DeviceObject() { reset(); }
    DeviceObject(DeviceObject&& o) noexcept : device_(o.device_), handle_(std::exchange(o.handle_, VK_NULL_HANDLE)) {}
    DeviceObject& operator=(DeviceObject&& o) noexcept {
        if (this != &o) {
            reset();
            device_ = o.device_;
            handle_ = std::exchange(o.handle_, VK_NULL_HANDLE);
        }
        return *this;
    }
    DeviceObject(const DeviceObject&) = delete;
    DeviceObject& operator=(const DeviceObject&) = delete;

    Handle get() const { return handle_; }
    operator Handle() const { return handle_; }  // pass straight to vk* calls
    const Handle* ptr() const { return &handle_; }
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

    void reset() {
        if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    Handle handle_ = VK_NULL_HANDLE;
};

using UniqueBuffer = DeviceObject<VkBuffer, vkDestroyBuffer>;
using UniqueDeviceMemory = DeviceObject<VkDeviceMemory, vkFreeMemory>;
using UniqueImage = DeviceObject<VkImage, vkDestroyImage>;
using UniqueImageView = DeviceObject<VkImageView, vkDestroyImageView>;
using UniqueSampler = DeviceObject<VkSampler, vkDestroySampler>;
using UniqueShaderModule = DeviceObject<VkShaderModule, vkDestroyShaderModule>;
using UniquePipeline = DeviceObject<VkPipeline, vkDestroyPipeline>;
using UniquePipelineLayout = DeviceObject<VkPipelineLayout, vkDestroyPipelineLayout>;
using UniqueDescriptorSetLayout = DeviceObject<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using UniqueDescriptorPool = DeviceObject<VkDescriptorPool, vkDestroyDescriptorPool>;
using UniqueCommandPool = DeviceObject<VkCommandPool, vkDestroyCommandPool>;
using UniqueFence = DeviceObject<VkFence, vkDestroyFence>;
using UniqueQueryPool = DeviceObject<VkQueryPool, vkDestroyQueryPool>;

}  // namespace hybridlab
