#pragma once
// The headless Vulkan 1.3 device of the raster core: no window, no swapchain, offscreen images
// only. It prefers a discrete GPU, then an integrated one, then a CPU device (Mesa lavapipe, the
// software rasteriser every machine of the project has); HYBRIDLAB_VULKAN_DEVICE=<part of a device
// name> picks by name (the tests pick lavapipe, "llvmpipe", whose results they were calibrated on).
// Validation layers are on in debug builds (or with HYBRIDLAB_VULKAN_VALIDATION=1) when installed.
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <vulkan/vulkan.h>

#include "common/raster/vk_unique.h"

namespace hybridlab {

class VulkanDevice {
public:
    // The process-wide device, created at first call. Throws VulkanUnavailable (with the reason)
    // when there is no Vulkan loader, no 1.3 device, or the device lacks what the raster core needs;
    // later calls throw the same error again.
    static std::shared_ptr<VulkanDevice> shared();

    ~VulkanDevice();
    VulkanDevice(const VulkanDevice&) = delete;
    VulkanDevice& operator=(const VulkanDevice&) = delete;

    VkDevice device() const { return device_; }
    VkPhysicalDevice physicalDevice() const { return physical_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    std::string name() const { return properties_.deviceName; }
    bool isLavapipe() const { return lavapipe_; }
    VkPhysicalDeviceType type() const { return properties_.deviceType; }
    // Whether pipeline-statistics queries are enabled (the device supports them; lavapipe does).
    bool pipelineStatistics() const { return pipelineStatistics_; }
    // The driver's name and version text, e.g. "llvmpipe, Mesa 25.0.7 (LLVM 15.0.6)".
    std::string driver() const { return std::string(driver_.driverName) + ", " + driver_.driverInfo; }
    float maxAnisotropy() const { return properties_.limits.maxSamplerAnisotropy; }
    // Nanoseconds per timestamp tick.
    double timestampPeriod() const { return properties_.limits.timestampPeriod; }

    // A memory type among `typeBits` with `flags`; throws VulkanError when there is none.
    std::uint32_t memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags flags) const;
    // Memory for a resource with requirements `req`: device-local, or host-visible and coherent
    // (cached where the device has it: read-back is then fast). `what` names it in errors.
    enum class MemoryUse { DeviceLocal, HostVisible };
    UniqueDeviceMemory allocate(const VkMemoryRequirements& req, MemoryUse use, const char* what) const;

    // Throws VulkanError naming the format and what it is needed for unless the format supports
    // `features` with optimal tiling.
    void requireFormat(VkFormat format, VkFormatFeatureFlags features, const char* purpose) const;

    // Records commands into a fresh one-time command buffer, submits it and waits for it.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;
    // Submits an already recorded command buffer and waits for it.
    void submitAndWait(VkCommandBuffer commands) const;

private:
    VulkanDevice() = default;
    void create();

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::uint32_t queueFamily_ = 0;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    VkPhysicalDeviceDriverProperties driver_{};
    bool lavapipe_ = false;
    bool pipelineStatistics_ = false;
    UniqueCommandPool pool_;
    UniqueFence fence_;
    mutable std::recursive_mutex submitMutex_;  // the queue, fence and pool: one submission at a time
};

}  // namespace hybridlab
