#pragma once
// A scene on the GPU, uploaded once: every mesh in one vertex and one index buffer, the materials,
// the textures (SceneTextures), and the objects' matrices at the current time (re-written when the
// time changes; deforming objects' vertices too). The geometry passes (G-buffer, shadow maps, visible pixels) draw through it, one
// draw per (object, mesh), culled against the pass's frustum.
#include <functional>
#include <memory>
#include <vector>

#include <glm/mat4x4.hpp>

#include "common/raster/gpu_buffer.h"
#include "common/raster/pipelines.h"
#include "common/raster/scene_textures.h"
#include "common/raster/shaders/raster_records.h"
#include "common/scene/deformed_mesh_cache.h"
#include "common/scene/scene.h"

namespace hybridlab {

// Push constants of the geometry passes (shaders/scene_data.glsl).
using raster_records::DrawConstants;
using raster_records::kHasTangentSpace;

struct MeshDraw {
    std::uint32_t object = 0;
    std::uint32_t mesh = 0;
    std::uint32_t material = 0;
    std::uint32_t firstIndex = 0;
    std::uint32_t indexCount = 0;
    std::int32_t vertexOffset = 0;
    std::uint32_t flags = 0;
    bool castsShadow = true;  // see GpuScene::castsShadow
    Aabb localBounds;
};

class GpuScene {
public:
    // Deformed vertices come from `deformedMeshes` when given (shared with the ray scene, see
    // deformed_mesh_cache.h; it must outlive this), else from a cache of its own.
    GpuScene(std::shared_ptr<VulkanDevice> device, const Scene& scene, DeformedMeshCache* deformedMeshes = nullptr);

    const Scene& scene() const { return scene_; }
    const VulkanDevice& device() const { return *device_; }

    // Moves animated objects to `time` and rewrites deforming objects' vertices (from the
    // DeformedMeshCache, which the ray scene can share); true when anything moved (first call
    // included). Dynamic objects are rewritten at an unchanged time too, as RayScene::setTime
    // re-commits them: a repeated frame of an animation costs what a new one does. Objects that
    // deform in place keep the draw records of their first placement.
    bool setTime(double time);

    // Set 0 of the geometry passes: the draw's object and material (binding 0, a dynamic uniform
    // buffer; recordDraw binds it at the draw's record).
    const DescriptorSet& descriptors() const { return descriptors_; }
    // Set 1 of the G-buffer pass, one per material: its diffuse (binding 0) and normal (1) texture.
    const DescriptorSet& materialTextures() const { return materialTextures_; }
    const SceneTextures& textures() const { return textures_; }

    // The vertex layout: position, normal, uv, tangent (48 bytes); depth-only passes read the position only.
    static std::vector<VkVertexInputBindingDescription> vertexBindings();
    static std::vector<VkVertexInputAttributeDescription> vertexAttributes(bool positionOnly);

    const std::vector<MeshDraw>& draws() const { return draws_; }
    const Aabb& worldBounds(std::size_t draw) const { return worldBounds_[draw]; }
    Aabb bounds() const;  // world space, at the current time
    // Draw indices of one object: [first, last).
    std::pair<std::size_t, std::size_t> objectDraws(std::uint32_t object) const { return objectDraws_[object]; }

    // Binds the vertex and index buffers.
    void bind(VkCommandBuffer cb) const;
    // One draw: its record as set 0, its push constants, and its material's textures as set 1 when `textures`.
    void recordDraw(VkCommandBuffer cb, VkPipelineLayout layout, const glm::mat4& viewProj, std::size_t draw, bool textures) const;
    // Every draw that `include` accepts (all without it) and that meets the frustum of `viewProj`;
    // returns how many.
    std::size_t recordDraws(VkCommandBuffer cb, VkPipelineLayout layout, const glm::mat4& viewProj, bool textures,
                            const std::function<bool(const MeshDraw&)>& include = {}) const;

    // A mesh goes into shadow maps when its material stops more than half of the light: shadow
    // maps are binary, so the occluder's transmittance (occluderTransmittance(), the shadow rule of
    // the ray tracer) is rounded to 0 or 1.
    static bool castsShadow(const Material& m);

private:
    void writeDeformedVertices(std::size_t object, double time);
    // The object's model matrix into its draw records, and their world bounds.
    void writePlacement(std::size_t object, double time);

    std::shared_ptr<VulkanDevice> device_;
    const Scene& scene_;
    SceneTextures textures_;
    GpuBuffer vertices_, indices_;
    GpuBuffer drawRecords_;  // one DrawRecord per draw, recordStride_ apart
    VkDeviceSize recordStride_ = 0;
    DescriptorSet descriptors_;
    DescriptorSet materialTextures_;
    std::vector<MeshDraw> draws_;
    std::vector<Aabb> worldBounds_;
    std::vector<std::pair<std::size_t, std::size_t>> objectDraws_;
    std::vector<std::int32_t> meshVertexOffset_;  // per mesh: its first vertex in vertices_
    std::unique_ptr<DeformedMeshCache> ownDeformedMeshes_;  // when none is shared
    DeformedMeshCache* deformedMeshes_ = nullptr;
    bool timeSet_ = false;
};

}  // namespace hybridlab
