#pragma once
// The scene on a ray-tracing Vulkan device (VK_KHR_acceleration_structure): what Embree's
// RayScene is on the CPU, built from the same Scene. A bottom-level acceleration structure per mesh
// (object space), one per mesh of each deforming object (refitted each frame from the
// DeformedMeshCache's vertices, which the rasterizer and Embree share: the topology stays, so an
// update replaces a rebuild, as RayScene's RTC_BUILD_QUALITY_REFIT); a top level of instances, one
// per (object, mesh), rebuilt when rigid objects move. Build, update and refit are timed as
// RayScene's are, with the same triangle counts.
#include <memory>
#include <vector>

#include "common/raster/gpu_buffer.h"
#include "common/raster/scene_textures.h"
#include "common/device_rays/shaders/device_ray_records.h"
#include "common/raster/vulkan_device.h"
#include "common/scene/deformed_mesh_cache.h"
#include "common/scene/scene.h"

namespace hybridlab {

// An acceleration structure with its storage.
class AccelerationStructure {
public:
    AccelerationStructure() = default;
    AccelerationStructure(const VulkanDevice& device, VkAccelerationStructureTypeKHR type, VkDeviceSize size);
    ~AccelerationStructure();
    AccelerationStructure(AccelerationStructure&& o) noexcept;
    AccelerationStructure& operator=(AccelerationStructure&& o) noexcept;

    VkAccelerationStructureKHR handle() const { return handle_; }
    VkDeviceAddress address() const { return address_; }
    VkDeviceSize size() const { return storage_.size(); }

private:
    const VulkanDevice* device_ = nullptr;
    GpuBuffer storage_;
    VkAccelerationStructureKHR handle_ = VK_NULL_HANDLE;
    VkDeviceAddress address_ = 0;
};

class DeviceRayScene {
public:
    // `device` must have DeviceFeatures::rayTracing. Deformed vertices come from `deformedMeshes`
    // (it must outlive this). Throws InputError when the scene does not fit in the device's memory.
    DeviceRayScene(std::shared_ptr<VulkanDevice> device, const Scene& scene, DeformedMeshCache& deformedMeshes, double time = 0.0);
    ~DeviceRayScene();

    const Scene& scene() const { return scene_; }
    const VulkanDevice& device() const { return *device_; }

    // Moves animated objects to `time` (instance transforms, top level rebuilt) and refits
    // deforming ones; at an unchanged time too, as RayScene::setTime.
    void setTime(double time);

    VkAccelerationStructureKHR topLevel() const { return topLevel_.handle(); }
    const GpuBuffer& materials() const { return materials_; }
    const GpuBuffer& lights() const { return lights_; }
    const GpuBuffer& instances() const { return instances_; }
    const GpuBuffer& vertices() const { return vertices_; }
    const GpuBuffer& indices() const { return indices_; }
    const GpuBuffer& instanceDescriptors() const { return instanceDescriptors_; }
    const SceneTextures& textures() const { return textures_; }
    std::uint32_t lightCount() const { return static_cast<std::uint32_t>(scene_.lights.size()); }

    double buildMilliseconds() const { return buildMs_; }
    double lastUpdateMilliseconds() const { return updateMs_; }
    std::size_t rigidMovingTriangles() const { return rigidMovingTriangles_; }
    std::size_t deformingTriangles() const { return deformingTriangles_; }
    std::size_t triangleCount() const { return triangles_; }
    // Device memory the acceleration structures and the scene's buffers hold.
    VkDeviceSize deviceBytes() const { return deviceBytes_; }

private:
    // One bottom level: a mesh's triangles at a range of the vertex and index buffers.
    struct BottomLevel {
        std::uint32_t mesh = 0;
        std::uint32_t firstVertex = 0, vertexCount = 0;
        std::uint32_t firstIndex = 0, triangleCount = 0;
        bool opaque = true;       // any-hit skipped: the material stops shadow rays
        bool deforming = false;   // built to be updated
        std::int32_t object = -1; // the deforming object, or -1 (shared by every object that uses the mesh)
        std::size_t deformedCopy = 0;  // deforming: its entry in deformedCopies_
        VkAccelerationStructureBuildSizesInfoKHR sizes{};
        AccelerationStructure structure;
    };
    struct InstanceRef {
        std::uint32_t object;
        std::uint32_t bottomLevel;
    };

    // The vertices and indices of every bottom level, one after another, as the device reads them.
    struct PackedGeometry {
        std::vector<device_rays::DeviceVertex> vertices;
        std::vector<std::uint32_t> indices;
    };
    // What the acceleration structures need: their storage, and scratch for the builds.
    struct StructureBytes {
        VkDeviceSize structures = 0, scratch = 0;
    };

    // The constructor's steps, in order.
    PackedGeometry gatherBottomLevels(double time);
    std::size_t addBottomLevel(PackedGeometry& packed, std::uint32_t mesh, std::int32_t object, const std::vector<glm::vec3>& positions);
    void uploadSceneBuffers(const PackedGeometry& packed);
    StructureBytes structureSizes();
    void requireDeviceMemory(const StructureBytes& bytes);
    void createStructures(VkDeviceSize scratchBytes);

    VkAccelerationStructureGeometryKHR triangleGeometry(const BottomLevel& b) const;
    void writeDeformedVertices(std::size_t object, double time);
    void writeInstances(double time);
    // Records builds (or updates) of `levels` and of the top level, and waits for them.
    void build(const std::vector<std::size_t>& levels, bool update);

    std::shared_ptr<VulkanDevice> device_;
    const Scene& scene_;
    DeformedMeshCache& deformedMeshes_;
    SceneTextures textures_;
    GpuBuffer materials_, lights_, instances_, vertices_, indices_;
    GpuBuffer deformedVertices_;                   // host-written: the deforming bottom levels' vertices, one after another
    std::vector<VkBufferCopy> deformedCopies_;     // per deforming bottom level: its range there and in vertices_
    GpuBuffer instanceDescriptors_;  // VkAccelerationStructureInstanceKHR per instance
    GpuBuffer scratch_;
    std::vector<BottomLevel> bottomLevels_;
    std::vector<InstanceRef> instanceRefs_;
    std::vector<std::vector<std::size_t>> objectBottomLevels_;  // per deforming object: its bottom levels
    AccelerationStructure topLevel_;
    VkAccelerationStructureBuildSizesInfoKHR topSizes_{};
    bool anyDynamic_ = false;
    std::size_t rigidMovingTriangles_ = 0, deformingTriangles_ = 0, triangles_ = 0;
    VkDeviceSize deviceBytes_ = 0;
    double buildMs_ = 0.0, updateMs_ = 0.0;
};

}  // namespace hybridlab
