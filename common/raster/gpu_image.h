#pragma once
// A Vulkan image with its own memory and a view of all its mip levels and layers, and the one
// layout-transition helper the passes use.
#include <cstdint>

#include "common/raster/vk_unique.h"
#include "common/raster/vulkan_device.h"

namespace hybridlab {

struct ImageDesc {
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    std::uint32_t width = 1, height = 1;
    std::uint32_t mipLevels = 1;
    std::uint32_t layers = 1;
    VkImageUsageFlags usage = 0;
    VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;
};

class GpuImage {
public:
    GpuImage() = default;
    GpuImage(const VulkanDevice& device, const ImageDesc& desc);

    VkImage image() const { return image_; }
    VkImageView view() const { return view_; }
    const ImageDesc& desc() const { return desc_; }
    VkImageAspectFlags aspect() const { return aspect_; }  // every aspect (depth and stencil for a combined format)
    bool valid() const { return static_cast<bool>(image_); }

    // A 2D view of one layer and mip level (render targets of layered images, storage levels of a pyramid).
    UniqueImageView layerView(std::uint32_t layer, std::uint32_t mip = 0) const;

private:
    VkDevice device_ = VK_NULL_HANDLE;
    ImageDesc desc_;
    VkImageAspectFlags aspect_ = VK_IMAGE_ASPECT_COLOR_BIT;
    UniqueImage image_;
    UniqueDeviceMemory memory_;
    UniqueImageView view_;
};

bool isDepthFormat(VkFormat format);
bool hasStencil(VkFormat format);

// One image memory barrier with a layout transition, over the given mip levels and layers.
void transitionImage(VkCommandBuffer cb, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                     VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage, VkAccessFlags dstAccess,
                     std::uint32_t baseMip = 0, std::uint32_t mipCount = VK_REMAINING_MIP_LEVELS, std::uint32_t baseLayer = 0,
                     std::uint32_t layerCount = VK_REMAINING_ARRAY_LAYERS);

}  // namespace hybridlab
