#include "common/raster/scene_textures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "common/image/color.h"
#include "common/raster/gpu_buffer.h"
#include "common/raster/pipelines.h"
#include "common/raster/vulkan_error.h"

namespace hybridlab {

namespace {

// The 8-bit sRGB code nearest a linear value. Colour textures were 8-bit sRGB decoded to linear on
// load, so this gives back their original bytes.
std::uint8_t srgbByte(float linear) {
    static const std::array<float, 256> decoded = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(static_cast<float>(i) / 255.0f);
        return t;
    }();
    const auto it = std::lower_bound(decoded.begin(), decoded.end(), linear);
    if (it == decoded.begin()) return 0;
    if (it == decoded.end()) return 255;
    const auto i = static_cast<std::uint8_t>(it - decoded.begin());
    return linear - *(it - 1) < *it - linear ? static_cast<std::uint8_t>(i - 1) : i;
}

std::uint8_t unormByte(float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// Copies `bytes` into mip 0 and layer 0.. of `image` (all layers packed one after the other), then
// either fills the mip chain by successive linear blits or leaves the one level; everything ends
// in SHADER_READ_ONLY_OPTIMAL.
void upload(const VulkanDevice& device, const GpuImage& image, const void* bytes, std::size_t size) {
    GpuBuffer staging(device, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, GpuBuffer::Memory::HostVisible);
    staging.write(bytes, size);
    const ImageDesc& d = image.desc();
    device.submitAndWait([&](VkCommandBuffer cb) {
        transitionImage(cb, image.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, d.layers};
        copy.imageExtent = {d.width, d.height, 1};
        vkCmdCopyBufferToImage(cb, staging.buffer(), image.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        std::int32_t w = static_cast<std::int32_t>(d.width), h = static_cast<std::int32_t>(d.height);
        for (std::uint32_t level = 1; level < d.mipLevels; ++level) {
            transitionImage(cb, image.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, level - 1, 1);
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, d.layers};
            blit.srcOffsets[1] = {w, h, 1};
            w = std::max(1, w / 2), h = std::max(1, h / 2);
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, d.layers};
            blit.dstOffsets[1] = {w, h, 1};
            vkCmdBlitImage(cb, image.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &blit, VK_FILTER_LINEAR);
            transitionImage(cb, image.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                            VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT, level - 1, 1);
        }
        transitionImage(cb, image.image(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT, d.mipLevels - 1, 1);
    });
}

GpuImage mipmappedTexture(const VulkanDevice& device, const Texture& texture) {
    const VkFormat format = texture.srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    device.requireFormat(format,
                         VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT |
                             VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT,
                         "mip-mapped textures");
    const Image& img = texture.image;
    const auto w = static_cast<std::uint32_t>(img.width()), h = static_cast<std::uint32_t>(img.height());
    const auto mips = static_cast<std::uint32_t>(std::floor(std::log2(static_cast<double>(std::max(w, h))))) + 1;
    GpuImage image(device, {format, w, h, mips, 1,
                            VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    std::vector<std::uint8_t> bytes(img.pixelCount() * 4);
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
        const glm::vec4 p = img.data()[i];
        for (int c = 0; c < 3; ++c) bytes[4 * i + c] = texture.srgb ? srgbByte(p[c]) : unormByte(p[c]);
        bytes[4 * i + 3] = unormByte(p.a);
    }
    upload(device, image, bytes.data(), bytes.size());
    return image;
}

}  // namespace

SceneTextures::SceneTextures(const VulkanDevice& device, const Scene& scene) {
    VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sci.magFilter = VK_FILTER_LINEAR;
    sci.minFilter = VK_FILTER_LINEAR;
    sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;  // as sampleBilinearWrap
    // Anisotropic filtering, except on lavapipe: Mesa 22.3's llvmpipe takes minutes per frame on
    // Sponza with any anisotropy (2x included), so there the filter is trilinear.
    sci.anisotropyEnable = device.isLavapipe() ? VK_FALSE : VK_TRUE;
    sci.maxAnisotropy = std::min(16.0f, device.maxAnisotropy());
    sci.maxLod = VK_LOD_CLAMP_NONE;
    VkSampler s;
    checkVk(vkCreateSampler(device.device(), &sci, nullptr, &s), "creating the texture sampler");
    anisotropic_ = UniqueSampler(device.device(), s);
    nearest_ = createNearestSampler(device, "a nearest sampler");

    std::vector<bool> used(scene.textures.size(), false);
    for (const Material& m : scene.materials) {
        if (m.diffuseTexture != kNoTexture) used[m.diffuseTexture] = true;
        if (m.normalTexture != kNoTexture) used[m.normalTexture] = true;
    }
    const std::uint8_t white[4] = {255, 255, 255, 255};
    whiteTexture_ = GpuImage(device, {VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1, 1, VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    upload(device, whiteTexture_, white, sizeof white);
    images_.resize(scene.textures.size());
    for (std::size_t i = 0; i < scene.textures.size(); ++i)
        if (used[i]) images_[i] = mipmappedTexture(device, scene.textures[i]);

    device.requireFormat(VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT, "the sky's cube faces");
    std::vector<glm::vec4> faces;
    std::uint32_t width = 1, height = 1;
    if (scene.sky.hasCubeMap()) {
        const Image& first = scene.textures[scene.sky.cubeFaces[0]].image;
        for (std::int32_t f : scene.sky.cubeFaces) {
            const Image& face = scene.textures[f].image;
            if (face.width() != first.width() || face.height() != first.height()) {
                throw VulkanError("the sky's cube-map faces must all be of one size (" + scene.textures[f].source + " is " +
                                  std::to_string(face.width()) + " x " + std::to_string(face.height()) + ")");
            }
            faces.insert(faces.end(), face.data(), face.data() + face.pixelCount());
        }
        width = static_cast<std::uint32_t>(first.width());
        height = static_cast<std::uint32_t>(first.height());
    } else {
        faces.assign(6, glm::vec4(0.0f));
    }
    sky_ = GpuImage(device, {VK_FORMAT_R32G32B32A32_SFLOAT, width, height, 1, 6, VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                             VK_IMAGE_VIEW_TYPE_2D_ARRAY});
    upload(device, sky_, faces.data(), faces.size() * sizeof(glm::vec4));
}

VkDescriptorImageInfo SceneTextures::texture(std::int32_t index) const {
    const bool real = index != kNoTexture && images_[static_cast<std::size_t>(index)].valid();
    return {anisotropic_, real ? images_[static_cast<std::size_t>(index)].view() : whiteTexture_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
}

}  // namespace hybridlab
