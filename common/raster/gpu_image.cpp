#include "common/raster/gpu_image.h"

#include <string>

#include "common/raster/vulkan_error.h"

namespace hybridlab {

bool isDepthFormat(VkFormat format) {
    return format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM || hasStencil(format);
}

bool hasStencil(VkFormat format) { return format == VK_FORMAT_D24_UNORM_S8_UINT || format == VK_FORMAT_D32_SFLOAT_S8_UINT; }

GpuImage::GpuImage(const VulkanDevice& device, const ImageDesc& desc)
    : device_(device.device()),
      desc_(desc),
      aspect_(hasStencil(desc.format)     ? VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT
              : isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT
                                           : VK_IMAGE_ASPECT_COLOR_BIT) {
    VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ici.flags = desc.viewType == VK_IMAGE_VIEW_TYPE_CUBE ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = desc.format;
    ici.extent = {desc.width, desc.height, 1};
    ici.mipLevels = desc.mipLevels;
    ici.arrayLayers = desc.layers;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.tiling = VK_IMAGE_TILING_OPTIMAL;
    ici.usage = desc.usage;
    ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage img;
    checkVk(vkCreateImage(device_, &ici, nullptr, &img), "creating an image");
    image_ = UniqueImage(device_, img);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, img, &req);
    try {
        memory_ = device.allocate(req, VulkanDevice::MemoryUse::DeviceLocal, "image");
        checkVk(vkBindImageMemory(device_, img, memory_, 0), "binding image memory");
    } catch (const VulkanError& e) {
        // Out of memory, say for what: the size the settings asked for (a shadow map's resolution,
        // the lights' count, the frame's size) is the user's to lower.
        throw VulkanError(std::string(e.what()) + ", for a " + std::to_string(desc.width) + " x " + std::to_string(desc.height) + " image" +
                          (desc.layers > 1 ? " of " + std::to_string(desc.layers) + " layers" : std::string()) + " (" +
                          std::to_string((req.size + (1u << 20) - 1) >> 20) + " MiB)");
    }

    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = img;
    vci.viewType = desc.viewType;
    vci.format = desc.format;
    vci.subresourceRange = {aspect_, 0, desc.mipLevels, 0, desc.layers};
    VkImageView view;
    checkVk(vkCreateImageView(device_, &vci, nullptr, &view), "creating an image view");
    view_ = UniqueImageView(device_, view);
}

UniqueImageView GpuImage::layerView(std::uint32_t layer, std::uint32_t mip) const {
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = image_;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = desc_.format;
    vci.subresourceRange = {aspect_, mip, 1, layer, 1};
    VkImageView view;
    checkVk(vkCreateImageView(device_, &vci, nullptr, &view), "creating an image layer view");
    return UniqueImageView(device_, view);
}

void transitionImage(VkCommandBuffer cb, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                     VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage, VkAccessFlags dstAccess,
                     std::uint32_t baseMip, std::uint32_t mipCount, std::uint32_t baseLayer, std::uint32_t layerCount) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, baseMip, mipCount, baseLayer, layerCount};
    vkCmdPipelineBarrier(cb, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

}  // namespace hybridlab
