#include "common/raster/shadow_maps.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "common/raster/frustum.h"
#include "common/raster/vulkan_error.h"
#include "common/scene/camera.h"

namespace hybridlab {

namespace {

constexpr VkFormat kFormat = VK_FORMAT_D32_SFLOAT;

std::array<glm::vec3, 8> corners(const Aabb& b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i) c[i] = {i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z};
    return c;
}

// Orthographic projection of the view-space box [l, r] x [b, t] x [-f, -n] into Vulkan clip space
// with y down and reverse-Z (near 1, far 0), as Camera::projectionMatrix.
glm::mat4 orthoReverseZ(float l, float r, float b, float t, float n, float f) {
    glm::mat4 p(0.0f);
    p[0][0] = 2.0f / (r - l);
    p[3][0] = -(r + l) / (r - l);
    p[1][1] = -2.0f / (t - b);
    p[3][1] = (t + b) / (t - b);
    p[2][2] = 1.0f / (f - n);
    p[3][2] = f / (f - n);
    p[3][3] = 1.0f;
    return p;
}

// A directional light's layer: an orthographic view along the light fitted to the scene's box.
ShadowLayerData directionalLayer(const Light& light, const Aabb& scene, std::uint32_t resolution) {
    const glm::vec3 centre = scene.center();
    const float radius = std::max(0.5f * glm::length(scene.extent()), 1e-3f);
    Camera c;
    c.position = centre - light.direction * (2.0f * radius);
    c.orientation = Camera::lookAtOrientation(c.position, centre);
    const glm::mat4 view = c.view();
    Aabb v;
    for (const glm::vec3& p : corners(scene)) v.extend(glm::vec3(view * glm::vec4(p, 1.0f)));
    const float margin = 0.01f * radius;
    const glm::mat4 proj = orthoReverseZ(v.lo.x - margin, v.hi.x + margin, v.lo.y - margin, v.hi.y + margin,
                                         std::max(0.0f, -v.hi.z - margin), -v.lo.z + margin);
    const float texel = (std::max(v.hi.x - v.lo.x, v.hi.y - v.lo.y) + 2.0f * margin) / static_cast<float>(resolution);
    return {proj * view, glm::vec4(texel, 0.0f, 0.0f, 0.0f)};
}

// A perspective layer from `position` looking along `direction` with a square field of view.
ShadowLayerData perspectiveLayer(glm::vec3 position, glm::vec3 direction, glm::vec3 up, float fovYDegrees, const Aabb& scene,
                                 std::uint32_t resolution) {
    float far = 0.0f;
    for (const glm::vec3& p : corners(scene)) far = std::max(far, glm::length(p - position));
    Camera c;
    c.position = position;
    c.orientation = Camera::lookAtOrientation(position, position + direction, up);
    c.fovYDegrees = fovYDegrees;
    c.farPlane = std::max(far * 1.01f, 0.1f);
    c.nearPlane = std::max(1e-3f * c.farPlane, 0.01f);
    const float texelPerDistance = 2.0f * std::tan(glm::radians(fovYDegrees) * 0.5f) / static_cast<float>(resolution);
    return {c.projectionMatrix(1.0f) * c.view(), glm::vec4(texelPerDistance, 1.0f, 0.0f, 0.0f)};
}

}  // namespace

ShadowMaps::ShadowMaps(const GpuScene& scene) : scene_(scene) {
    const VulkanDevice& device = scene.device();
    device.requireFormat(kFormat, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT, "shadow maps");
    layout_ = createPipelineLayout(device, {scene.descriptors().layout()}, sizeof(DrawConstants));
    GraphicsPipelineDesc d;
    d.vertexShader = "depth_only.vert";
    d.vertexBindings = GpuScene::vertexBindings();
    d.vertexAttributes = GpuScene::vertexAttributes(true);
    d.depthFormat = kFormat;
    d.depthTest = true;
    d.depthWrite = true;
    d.depthCompare = VK_COMPARE_OP_GREATER;
    d.dynamicDepthBias = true;
    d.layout = layout_;
    pipeline_ = createGraphicsPipeline(device, d);

    VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    // Nearest: the shader gathers 2 x 2 comparisons and filters them itself (lavapipe cannot filter
    // D32 linearly).
    sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
    sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sci.compareEnable = VK_TRUE;
    sci.compareOp = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reverse-Z: lit where the receiver is at least as near as the caster
    VkSampler s;
    checkVk(vkCreateSampler(device.device(), &sci, nullptr, &s), "creating the shadow-map sampler");
    sampler_ = UniqueSampler(device.device(), s);

    const auto& lights = scene.scene().lights;
    int next = 0;
    for (const Light& l : lights) {
        const int n = !l.castsShadows ? 0 : l.type == Light::Type::Point ? 6 : 1;
        first_.push_back(n ? next : -1);
        count_.push_back(n);
        next += n;
    }
    layers_.resize(static_cast<std::size_t>(next));
    const VkDeviceSize bytes = std::max<std::size_t>(1, layers_.size()) * sizeof(ShadowLayerData);
    if (bytes > device.properties().limits.maxUniformBufferRange) {
        throw VulkanUnavailable("Vulkan device " + device.name() + " takes uniform buffers up to " +
                                std::to_string(device.properties().limits.maxUniformBufferRange) + " bytes; the shadow maps of " +
                                std::to_string(lights.size()) + " lights need " + std::to_string(bytes));
    }
    layerBuffer_ = GpuBuffer(device, bytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Memory::DeviceLocalHostVisible);
    // Until shadows are first rendered, an empty 1 x 1 map keeps the lighting pass's binding valid.
    image_ = GpuImage(device, {kFormat, 1, 1, 1, 1, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                               VK_IMAGE_VIEW_TYPE_2D_ARRAY});
    device.submitAndWait([&](VkCommandBuffer cb) {
        transitionImage(cb, image_.image(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    });
}

void ShadowMaps::layOut(const ShadowSettings& settings) {
    const VulkanDevice& device = scene_.device();
    const auto layers = static_cast<std::uint32_t>(std::max<std::size_t>(1, layers_.size()));
    image_ = GpuImage(device, {kFormat, settings.resolution, settings.resolution, 1, layers,
                               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_VIEW_TYPE_2D_ARRAY});
    layerViews_.clear();
    for (std::uint32_t i = 0; i < layers_.size(); ++i) layerViews_.push_back(image_.layerView(i));
}

bool ShadowMaps::record(VkCommandBuffer cb, const ShadowSettings& settings, bool sceneMoved) {
    if (rendered_ && !sceneMoved && settings == current_) return false;
    if (!rendered_ || settings.resolution != current_.resolution) layOut(settings);
    current_ = settings;
    rendered_ = true;

    // Layer matrices from the scene's bounds now (moving objects change them).
    const Aabb bounds = scene_.bounds();
    const auto& lights = scene_.scene().lights;
    // Cube faces a little wider than 90 degrees, so that PCF taps near a face's edge stay on it.
    const float cubeFov = 2.0f * glm::degrees(std::atan(1.0f + 2.0f * static_cast<float>(settings.pcfRadius + 2) / settings.resolution));
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (std::size_t i = 0; i < lights.size(); ++i) {
        if (first_[i] < 0) continue;
        const Light& l = lights[i];
        ShadowLayerData* layer = &layers_[static_cast<std::size_t>(first_[i])];
        if (l.type == Light::Type::Directional) {
            *layer = directionalLayer(l, bounds, settings.resolution);
        } else if (l.type == Light::Type::Spot) {
            const float fov = std::min(2.0f * l.outerConeDegrees + 2.0f, 170.0f);
            *layer = perspectiveLayer(l.position, l.direction, {0, 1, 0}, fov, bounds, settings.resolution);
        } else {
            for (int f = 0; f < 6; ++f) layer[f] = perspectiveLayer(l.position, axes[f], f == 2 || f == 3 ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0), cubeFov, bounds, settings.resolution);
        }
    }
    if (!layers_.empty()) layerBuffer_.write(layers_.data(), layers_.size() * sizeof(ShadowLayerData));

    transitionImage(cb, image_.image(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                    VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    for (std::size_t i = 0; i < layers_.size(); ++i) {
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = layerViews_[i];
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = {0.0f, 0};
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = {{0, 0}, {settings.resolution, settings.resolution}};
        ri.layerCount = 1;
        ri.pDepthAttachment = &depth;
        vkCmdBeginRendering(cb, &ri);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
        setViewport(cb, settings.resolution, settings.resolution);
        // Reverse-Z: a negative bias pushes the stored depth away from the light.
        vkCmdSetDepthBias(cb, -1.0f, 0.0f, -settings.slopeBias);
        scene_.bind(cb);
        scene_.recordDraws(cb, layout_, layers_[i].viewProj, false, [](const MeshDraw& d) { return d.castsShadow; });
        vkCmdEndRendering(cb);
    }
    transitionImage(cb, image_.image(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    return true;
}

}  // namespace hybridlab
