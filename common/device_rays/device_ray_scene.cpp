#include "common/device_rays/device_ray_scene.h"

#include <cstdio>
#include <cstring>
#include <string>

#include "common/core/input_error.h"
#include "common/core/wall_clock.h"
#include "common/raster/light_record.h"
#include "common/raster/vulkan_error.h"
#include "common/raytrace/shading.h"
#include "common/scene/transform.h"

namespace hybridlab {

using namespace device_rays;

namespace {

constexpr VkBufferUsageFlags kBuildInput =
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

DeviceMaterial deviceMaterial(const Material& m) {
    DeviceMaterial d;
    d.emission = glm::vec4(m.emission, 0.0f);
    d.ambient = glm::vec4(m.ambient, 0.0f);
    d.diffuse = glm::vec4(m.diffuse, 0.0f);
    d.specular = glm::vec4(m.specular, m.specularExponent);
    d.optical = glm::vec4(m.reflectivity, m.ior, m.opacity, m.fresnel ? 1.0f : 0.0f);
    d.absorption = glm::vec4(m.absorption, m.castsShadows ? 1.0f : 0.0f);
    d.tilingOffset = glm::vec4(m.textureTiling, m.textureOffset);
    d.textures = glm::ivec4(m.diffuseTexture, m.normalTexture, 0, 0);
    return d;
}

DeviceVertex deviceVertex(const glm::vec3& p, const glm::vec3& n, glm::vec2 uv, glm::vec4 tangent) {
    return {glm::vec4(p, uv.x), glm::vec4(n, uv.y), tangent};
}

}  // namespace

AccelerationStructure::AccelerationStructure(const VulkanDevice& device, VkAccelerationStructureTypeKHR type, VkDeviceSize size)
    : device_(&device),
      storage_(device, size, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
               GpuBuffer::Memory::DeviceLocal) {
    VkAccelerationStructureCreateInfoKHR ci{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
    ci.buffer = storage_.buffer();
    ci.size = size;
    ci.type = type;
    checkVk(device.rayTracing().createAccelerationStructure(device.device(), &ci, nullptr, &handle_), "creating an acceleration structure");
    VkAccelerationStructureDeviceAddressInfoKHR ai{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
    ai.accelerationStructure = handle_;
    address_ = device.rayTracing().getAccelerationStructureDeviceAddress(device.device(), &ai);
}

AccelerationStructure::~AccelerationStructure() {
    if (handle_) device_->rayTracing().destroyAccelerationStructure(device_->device(), handle_, nullptr);
}

AccelerationStructure::AccelerationStructure(AccelerationStructure&& o) noexcept
    : device_(o.device_), storage_(std::move(o.storage_)), handle_(o.handle_), address_(o.address_) {
    o.handle_ = VK_NULL_HANDLE;
}

AccelerationStructure& AccelerationStructure::operator=(AccelerationStructure&& o) noexcept {
    if (this != &o) {
        if (handle_) device_->rayTracing().destroyAccelerationStructure(device_->device(), handle_, nullptr);
        device_ = o.device_;
        storage_ = std::move(o.storage_);
        handle_ = o.handle_;
        address_ = o.address_;
        o.handle_ = VK_NULL_HANDLE;
    }
    return *this;
}

DeviceRayScene::DeviceRayScene(std::shared_ptr<VulkanDevice> device, const Scene& scene, DeformedMeshCache& deformedMeshes, double time)
    : device_(std::move(device)), scene_(scene), deformedMeshes_(deformedMeshes), textures_(*device_, scene) {
    const auto start = WallClock::now();
    // A pending ray's medium stack packs object and material in 16 bits each (device_medium_stack.glsl).
    if (scene_.objects.size() >= 0xFFFF || scene_.materials.size() >= 0xFFFF)
        throw InputError("scene " + scene_.name + " has " + std::to_string(scene_.objects.size()) + " objects and " +
                         std::to_string(scene_.materials.size()) + " materials; rays = \"vulkan\" addresses at most 65534 of each");
    uploadSceneBuffers(gatherBottomLevels(time));
    const StructureBytes bytes = structureSizes();
    requireDeviceMemory(bytes);
    createStructures(bytes.scratch);
    writeInstances(time);
    std::vector<std::size_t> all(bottomLevels_.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    build(all, false);
    buildMs_ = millisecondsSince(start);
}

// Bottom levels: every mesh once, in object space; deforming objects' meshes each their own.
DeviceRayScene::PackedGeometry DeviceRayScene::gatherBottomLevels(double time) {
    const std::size_t n = scene_.objects.size();
    PackedGeometry packed;
    std::vector<std::int32_t> sharedLevel(scene_.meshes.size(), -1);
    objectBottomLevels_.resize(n);
    for (std::size_t o = 0; o < n; ++o) {
        const SceneObject& object = scene_.objects[o];
        triangles_ += scene_.objectTriangleCount(o);
        anyDynamic_ |= object.isDynamic();
        if (object.isDeforming()) {
            deformingTriangles_ += scene_.objectTriangleCount(o);
            const std::vector<DeformedVertices>& deformed = deformedMeshes_.vertices(o, time, DeformedMeshCache::kDeviceRays);
            for (std::size_t k = 0; k < object.meshes.size(); ++k) {
                const std::size_t level = addBottomLevel(packed, object.meshes[k], static_cast<std::int32_t>(o), deformed[k].positions);
                objectBottomLevels_[o].push_back(level);
                instanceRefs_.push_back({static_cast<std::uint32_t>(o), static_cast<std::uint32_t>(level)});
            }
            continue;
        }
        if (object.isAnimated()) rigidMovingTriangles_ += scene_.objectTriangleCount(o);
        for (std::uint32_t mesh : object.meshes) {
            if (sharedLevel[mesh] < 0)
                sharedLevel[mesh] = static_cast<std::int32_t>(addBottomLevel(packed, mesh, -1, scene_.meshes[mesh].positions));
            instanceRefs_.push_back({static_cast<std::uint32_t>(o), static_cast<std::uint32_t>(sharedLevel[mesh])});
        }
    }
    return packed;
}

// One bottom level of `mesh` at `positions` (the deforming `object`'s, or -1: the mesh's own),
// its vertices and indices appended to `packed`; returns its index.
std::size_t DeviceRayScene::addBottomLevel(PackedGeometry& packed, std::uint32_t mesh, std::int32_t object,
                                           const std::vector<glm::vec3>& positions) {
    const Mesh& m = scene_.meshes[mesh];
    const Material& mat = scene_.materials[m.material];
    BottomLevel b;
    b.mesh = mesh;
    b.object = object;
    b.deforming = object >= 0;
    // Opaque geometry skips the shadow any-hit; the others are RayScene's filtered geometry.
    b.opaque = !(mat.isRefractive() || !mat.castsShadows);
    b.firstVertex = static_cast<std::uint32_t>(packed.vertices.size());
    b.vertexCount = static_cast<std::uint32_t>(positions.size());
    b.firstIndex = static_cast<std::uint32_t>(packed.indices.size());
    b.triangleCount = static_cast<std::uint32_t>(m.triangles.size());
    for (std::size_t i = 0; i < positions.size(); ++i) {
        packed.vertices.push_back(deviceVertex(positions[i], m.normals[i], m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[i],
                                               m.tangents.empty() ? glm::vec4(0.0f) : m.tangents[i]));
    }
    for (const glm::uvec3& t : m.triangles) packed.indices.insert(packed.indices.end(), {t.x, t.y, t.z});
    bottomLevels_.push_back(std::move(b));
    return bottomLevels_.size() - 1;
}

void DeviceRayScene::uploadSceneBuffers(const PackedGeometry& packed) {
    const VulkanDevice& dev = *device_;
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    using Memory = GpuBuffer::Memory;
    const auto& vertices = packed.vertices;
    const auto& indices = packed.indices;
    // What every ray reads lies in device memory: on a GPU, host memory is read across PCIe.
    vertices_ = GpuBuffer::withData(dev, vertices.data(), vertices.size() * sizeof(DeviceVertex), storage | kBuildInput);
    // Deforming objects' vertices are rewritten each frame: written here, copied into vertices_
    // before their refit (build).
    VkDeviceSize staged = 0;
    for (BottomLevel& b : bottomLevels_) {
        if (!b.deforming) continue;
        b.deformedCopy = deformedCopies_.size();
        deformedCopies_.push_back({staged, VkDeviceSize(b.firstVertex) * sizeof(DeviceVertex), VkDeviceSize(b.vertexCount) * sizeof(DeviceVertex)});
        staged += deformedCopies_.back().size;
    }
    if (staged > 0) deformedVertices_ = GpuBuffer(dev, staged, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, Memory::HostVisible);
    indices_ = GpuBuffer::withData(dev, indices.data(), indices.size() * sizeof(std::uint32_t), storage | kBuildInput);
    std::vector<DeviceMaterial> materials;
    for (const Material& m : scene_.materials) materials.push_back(deviceMaterial(m));
    materials_ = GpuBuffer::withData(dev, materials.data(), materials.size() * sizeof(DeviceMaterial), storage);
    // No shadow maps here: shadow.x says only whether the light casts shadows (0) or not (-1).
    std::vector<LightData> lights;
    for (const Light& l : scene_.lights) lights.push_back(lightRecord(l, l.castsShadows ? 0 : -1, 0));
    lights_ = GpuBuffer::withData(dev, lights.data(), lights.size() * sizeof(LightData), storage);
    // Rewritten when objects move (writeInstances), read by every ray and by the top level's build.
    instances_ = GpuBuffer(dev, instanceRefs_.size() * sizeof(DeviceInstance), storage, Memory::DeviceLocalHostVisible);
    instanceDescriptors_ =
        GpuBuffer(dev, instanceRefs_.size() * sizeof(VkAccelerationStructureInstanceKHR), kBuildInput, Memory::DeviceLocalHostVisible);
}

// Sizes: every bottom level, the top level, one scratch buffer for the largest build.
DeviceRayScene::StructureBytes DeviceRayScene::structureSizes() {
    const VulkanDevice& dev = *device_;
    VkPhysicalDeviceAccelerationStructurePropertiesKHR asProps{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &asProps};
    vkGetPhysicalDeviceProperties2(dev.physicalDevice(), &p2);
    const VkDeviceSize scratchAlign = std::max<VkDeviceSize>(asProps.minAccelerationStructureScratchOffsetAlignment, 16);
    StructureBytes bytes;
    for (BottomLevel& b : bottomLevels_) {
        b.sizes.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR;
        VkAccelerationStructureGeometryKHR g = triangleGeometry(b);
        VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
        info.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
        info.flags = b.deforming ? VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR | VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_BUILD_BIT_KHR
                                 : VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
        info.geometryCount = 1;
        info.pGeometries = &g;
        dev.rayTracing().getAccelerationStructureBuildSizes(dev.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info,
                                                           &b.triangleCount, &b.sizes);
        bytes.structures += b.sizes.accelerationStructureSize;
        bytes.scratch += alignUp(std::max(b.sizes.buildScratchSize, b.sizes.updateScratchSize), scratchAlign);
    }
    {
        VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
        g.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
        g.geometry.instances = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR};
        VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
        info.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
        info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
        info.geometryCount = 1;
        info.pGeometries = &g;
        const auto count = static_cast<std::uint32_t>(instanceRefs_.size());
        topSizes_.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR;
        dev.rayTracing().getAccelerationStructureBuildSizes(dev.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info, &count,
                                                           &topSizes_);
        bytes.structures += topSizes_.accelerationStructureSize;
        bytes.scratch = std::max(bytes.scratch, alignUp(topSizes_.buildScratchSize, scratchAlign));
    }
    return bytes;
}

// Refuses a scene whose structures and buffers do not fit in the device's memory (InputError).
void DeviceRayScene::requireDeviceMemory(const StructureBytes& bytes) {
    const VulkanDevice& dev = *device_;
    deviceBytes_ = bytes.structures + bytes.scratch + vertices_.size() + indices_.size() + materials_.size() + instances_.size();
    if (deviceBytes_ > dev.deviceLocalBytes()) {
        auto mib = [](VkDeviceSize count) {
            char text[32];
            std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(count) / (1 << 20));
            return std::string(text);
        };
        throw InputError("scene " + scene_.name + " (" + std::to_string(triangles_) + " triangles) needs " + mib(deviceBytes_) +
                         " of device memory for its acceleration structures and buffers; " + dev.name() + " has " +
                         mib(dev.deviceLocalBytes()));
    }
}

void DeviceRayScene::createStructures(VkDeviceSize scratchBytes) {
    const VulkanDevice& dev = *device_;
    scratch_ = GpuBuffer(dev, scratchBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, GpuBuffer::Memory::DeviceLocal);
    for (BottomLevel& b : bottomLevels_) {
        b.structure = AccelerationStructure(dev, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, b.sizes.accelerationStructureSize);
    }
    topLevel_ = AccelerationStructure(dev, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, topSizes_.accelerationStructureSize);
}

DeviceRayScene::~DeviceRayScene() = default;

VkAccelerationStructureGeometryKHR DeviceRayScene::triangleGeometry(const BottomLevel& b) const {
    VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    g.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
    g.flags = b.opaque ? VK_GEOMETRY_OPAQUE_BIT_KHR : 0;
    auto& t = g.geometry.triangles;
    t = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR};
    t.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
    t.vertexData.deviceAddress = vertices_.valid() ? vertices_.deviceAddress(*device_) + VkDeviceSize(b.firstVertex) * sizeof(DeviceVertex) : 0;
    t.vertexStride = sizeof(DeviceVertex);
    t.maxVertex = b.vertexCount > 0 ? b.vertexCount - 1 : 0;
    t.indexType = VK_INDEX_TYPE_UINT32;
    t.indexData.deviceAddress = indices_.valid() ? indices_.deviceAddress(*device_) + VkDeviceSize(b.firstIndex) * sizeof(std::uint32_t) : 0;
    return g;
}

void DeviceRayScene::writeDeformedVertices(std::size_t object, double time) {
    const std::vector<DeformedVertices>& deformed = deformedMeshes_.vertices(object, time, DeformedMeshCache::kDeviceRays);
    auto* staging = static_cast<char*>(deformedVertices_.mapped());
    const std::vector<std::size_t>& levels = objectBottomLevels_[object];
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const BottomLevel& b = bottomLevels_[levels[k]];
        auto* out = reinterpret_cast<DeviceVertex*>(staging + deformedCopies_[b.deformedCopy].srcOffset);
        const Mesh& m = scene_.meshes[b.mesh];
        const DeformedVertices& d = deformed[k];
        for (std::size_t i = 0; i < d.positions.size(); ++i) {
            out[i] = deviceVertex(d.positions[i], d.normals[i], m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[i],
                                  d.tangents.empty() ? (m.tangents.empty() ? glm::vec4(0.0f) : m.tangents[i]) : d.tangents[i]);
        }
    }
}

void DeviceRayScene::writeInstances(double time) {
    auto* records = static_cast<DeviceInstance*>(instances_.mapped());
    auto* descriptors = static_cast<VkAccelerationStructureInstanceKHR*>(instanceDescriptors_.mapped());
    std::vector<glm::mat4> toWorld(scene_.objects.size());
    for (std::size_t o = 0; o < scene_.objects.size(); ++o) toWorld[o] = scene_.objects[o].worldMatrix(time);
    for (std::size_t i = 0; i < instanceRefs_.size(); ++i) {
        const InstanceRef& ref = instanceRefs_[i];
        const BottomLevel& b = bottomLevels_[ref.bottomLevel];
        const Mesh& m = scene_.meshes[b.mesh];
        const glm::mat4& M = toWorld[ref.object];
        DeviceInstance& r = records[i];
        r.toWorld = M;
        r.normalToWorld = glm::mat4(normalMatrix(M));
        r.geometry = glm::uvec4(ref.object, b.mesh, m.material, b.firstVertex);
        r.topology = glm::uvec4(b.firstIndex, (m.uvs.empty() ? 0u : kHasUvs) | (m.tangents.empty() ? 0u : kHasTangents), 0u, 0u);
        VkAccelerationStructureInstanceKHR& d = descriptors[i];
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 4; ++col) d.transform.matrix[row][col] = M[col][row];
        d.instanceCustomIndex = static_cast<std::uint32_t>(i);
        d.mask = 0xFF;
        d.instanceShaderBindingTableRecordOffset = 0;
        d.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
        d.accelerationStructureReference = b.structure.address();
    }
}

void DeviceRayScene::build(const std::vector<std::size_t>& levels, bool update) {
    const VulkanDevice& dev = *device_;
    VkPhysicalDeviceAccelerationStructurePropertiesKHR asProps{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &asProps};
    vkGetPhysicalDeviceProperties2(dev.physicalDevice(), &p2);
    const VkDeviceSize scratchAlign = std::max<VkDeviceSize>(asProps.minAccelerationStructureScratchOffsetAlignment, 16);
    const VkDeviceAddress scratch = scratch_.deviceAddress(dev);

    std::vector<VkAccelerationStructureGeometryKHR> geometries(levels.size());
    std::vector<VkAccelerationStructureBuildGeometryInfoKHR> infos(levels.size());
    std::vector<VkAccelerationStructureBuildRangeInfoKHR> ranges(levels.size());
    std::vector<const VkAccelerationStructureBuildRangeInfoKHR*> rangePointers(levels.size());
    VkDeviceSize offset = 0;
    for (std::size_t i = 0; i < levels.size(); ++i) {
        BottomLevel& b = bottomLevels_[levels[i]];
        geometries[i] = triangleGeometry(b);
        VkAccelerationStructureBuildGeometryInfoKHR& info = infos[i];
        info = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
        info.type = VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR;
        info.flags = b.deforming ? VK_BUILD_ACCELERATION_STRUCTURE_ALLOW_UPDATE_BIT_KHR | VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_BUILD_BIT_KHR
                                 : VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
        info.mode = update ? VK_BUILD_ACCELERATION_STRUCTURE_MODE_UPDATE_KHR : VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
        info.srcAccelerationStructure = update ? b.structure.handle() : VK_NULL_HANDLE;  // refitted in place
        info.dstAccelerationStructure = b.structure.handle();
        info.geometryCount = 1;
        info.pGeometries = &geometries[i];
        info.scratchData.deviceAddress = scratch + offset;
        offset += alignUp(std::max(b.sizes.buildScratchSize, b.sizes.updateScratchSize), scratchAlign);
        ranges[i] = {b.triangleCount, 0, 0, 0};
        rangePointers[i] = &ranges[i];
    }

    VkAccelerationStructureGeometryKHR top{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    top.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
    top.geometry.instances = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR};
    top.geometry.instances.data.deviceAddress = instanceDescriptors_.deviceAddress(dev);
    VkAccelerationStructureBuildGeometryInfoKHR topInfo{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    topInfo.type = VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
    topInfo.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
    topInfo.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    topInfo.dstAccelerationStructure = topLevel_.handle();
    topInfo.geometryCount = 1;
    topInfo.pGeometries = &top;
    topInfo.scratchData.deviceAddress = scratch;
    const VkAccelerationStructureBuildRangeInfoKHR topRange{static_cast<std::uint32_t>(instanceRefs_.size()), 0, 0, 0};
    const VkAccelerationStructureBuildRangeInfoKHR* topRangePointer = &topRange;

    dev.submitAndWait([&](VkCommandBuffer cb) {
        if (update && !deformedCopies_.empty()) {
            // The deformed vertices written by the host, into the device's vertex buffer for the refits.
            vkCmdCopyBuffer(cb, deformedVertices_.buffer(), vertices_.buffer(), static_cast<std::uint32_t>(deformedCopies_.size()),
                            deformedCopies_.data());
            VkMemoryBarrier copied{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT};
            vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0, 1, &copied, 0,
                                 nullptr, 0, nullptr);
        }
        if (!infos.empty()) {
            dev.rayTracing().cmdBuildAccelerationStructures(cb, static_cast<std::uint32_t>(infos.size()), infos.data(), rangePointers.data());
            // The top level reads the bottom levels and reuses their scratch memory.
            VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
            barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
            barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
            vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                                 0, 1, &barrier, 0, nullptr, 0, nullptr);
        }
        dev.rayTracing().cmdBuildAccelerationStructures(cb, 1, &topInfo, &topRangePointer);
    });
}

void DeviceRayScene::setTime(double time) {
    const auto start = WallClock::now();
    if (anyDynamic_) {
        std::vector<std::size_t> refit;
        for (std::size_t o = 0; o < scene_.objects.size(); ++o) {
            if (!scene_.objects[o].isDeforming()) continue;
            writeDeformedVertices(o, time);
            refit.insert(refit.end(), objectBottomLevels_[o].begin(), objectBottomLevels_[o].end());
        }
        writeInstances(time);
        build(refit, true);
    }
    updateMs_ = millisecondsSince(start);
}

}  // namespace hybridlab
