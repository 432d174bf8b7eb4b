#pragma once
// Errors of the raster core. Everything that can go wrong with Vulkan becomes an exception with a
// message that says what failed and why (DESIGN.md "Conventions"), never a crash.
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace hybridlab {

class VulkanError : public std::runtime_error {
public:
    explicit VulkanError(const std::string& message) : std::runtime_error(message) {}
};

// No Vulkan loader, instance or usable device: the raster techniques cannot run on this machine.
class VulkanUnavailable : public VulkanError {
public:
    explicit VulkanUnavailable(const std::string& message) : VulkanError(message) {}
};

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" and the like.
const char* vkResultName(VkResult result);

// Throws VulkanError("Vulkan: <what> failed: <result>") unless `result` is VK_SUCCESS.
void checkVk(VkResult result, const char* what);

}  // namespace hybridlab
