#pragma once
// Shadow maps for the raster-only path and for techniques that choose them: one depth layer per
// directional light (orthographic, fitted to the scene's bounds) and per spot light (perspective
// over its outer cone), six per point light (a cube map as six 90-degree faces, picked by the major
// axis of the light-to-point vector). All layers share one D32 array image, reverse-Z like the
// G-buffer. Against acne: slope-scaled depth bias when rendering and a normal offset of a few
// texels when looking up; PCF over a (2r + 1)^2 footprint of bilinearly filtered comparisons.
// Materials that let half the light or more through are not shadow casters (GpuScene::castsShadow).
#include <vector>

#include <glm/mat4x4.hpp>

#include "common/raster/gpu_image.h"
#include "common/raster/gpu_scene.h"
#include "common/raster/raster_options.h"
#include "common/raster/shaders/raster_records.h"

namespace hybridlab {

// One layer as the lighting pass reads it (shaders/raster_records.h).
using ShadowLayerData = raster_records::ShadowLayer;

class ShadowMaps {
public:
    explicit ShadowMaps(const GpuScene& scene);

    // Renders every layer when the settings changed, anything moved, or nothing was rendered yet;
    // returns whether it rendered. Leaves the image in DEPTH_STENCIL_READ_ONLY_OPTIMAL.
    bool record(VkCommandBuffer cb, const ShadowSettings& settings, bool sceneMoved);

    // Per light: its first layer, or -1 when it casts no shadow; and its layer count (1 or 6).
    int firstLayer(std::size_t light) const { return first_[light]; }
    int layerCount(std::size_t light) const { return count_[light]; }
    std::size_t layers() const { return layers_.size(); }

    // For the lighting pass: the layer data and the depth array with a comparison sampler.
    VkBuffer layerBuffer() const { return layerBuffer_.buffer(); }
    VkDescriptorImageInfo depthArray() const { return {sampler_, image_.view(), VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL}; }

private:
    void layOut(const ShadowSettings& settings);

    const GpuScene& scene_;
    UniquePipelineLayout layout_;
    UniquePipeline pipeline_;
    UniqueSampler sampler_;
    std::vector<int> first_, count_;
    std::vector<ShadowLayerData> layers_;
    GpuBuffer layerBuffer_;
    GpuImage image_;
    std::vector<UniqueImageView> layerViews_;
    ShadowSettings current_;
    bool rendered_ = false;
};

}  // namespace hybridlab
