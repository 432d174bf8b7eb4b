#pragma once
// A scene's textures on the GPU, uploaded once per scene: material textures with full mip chains
// (sampled trilinearly with anisotropic filtering where the device does it well; sRGB ones as
// *_SRGB images, so the sampler decodes to linear before it filters), and the sky's cube faces as a float array image that the
// lighting pass reads exactly as skyRadiance() does.
#include <vector>

#include "common/raster/gpu_image.h"
#include "common/scene/scene.h"

namespace hybridlab {

class SceneTextures {
public:
    SceneTextures(const VulkanDevice& device, const Scene& scene);

    // Scene::textures[index] with the anisotropic sampler; for kNoTexture a white 1 x 1 texture (the
    // shading model's T = 1 for a material without one).
    VkDescriptorImageInfo texture(std::int32_t index) const;

    // The sky's six cube faces (+X, -X, +Y, -Y, +Z, -Z) as layers of an RGBA32F array image, or a
    // 1 x 1 x 6 image (unread) when the sky is a constant colour; with a nearest sampler (the shader
    // filters by hand, as the C++).
    VkDescriptorImageInfo sky() const { return {nearest_, sky_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}; }

private:
    std::vector<GpuImage> images_;
    GpuImage whiteTexture_;
    GpuImage sky_;
    UniqueSampler anisotropic_;
    UniqueSampler nearest_;
};

}  // namespace hybridlab
