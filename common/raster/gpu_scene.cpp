#include "common/raster/gpu_scene.h"

#include <algorithm>
#include <cstddef>

#include "common/raster/frustum.h"
#include "common/raytrace/shading.h"

namespace hybridlab {

namespace {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
    glm::vec4 tangent;
};
static_assert(sizeof(Vertex) == 48);

// Vertex v of `m`, with the attributes of `deformed` in place of the rest pose when given.
Vertex packVertex(const Mesh& m, std::size_t v, const DeformedVertices* deformed) {
    const std::vector<glm::vec3>& positions = deformed ? deformed->positions : m.positions;
    const std::vector<glm::vec3>& normals = deformed ? deformed->normals : m.normals;
    const std::vector<glm::vec4>& tangents = deformed ? deformed->tangents : m.tangents;
    return {positions[v], normals.empty() ? glm::vec3(0, 1, 0) : normals[v], m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[v],
            tangents.empty() ? glm::vec4(0.0f) : tangents[v]};
}

using raster_records::DrawRecord;
using raster_records::MaterialData;
using raster_records::ObjectData;

MaterialData materialData(const Material& m) {
    return {glm::vec4(m.emission, 0.0f),
            glm::vec4(m.ambient, 0.0f),
            glm::vec4(m.diffuse, 0.0f),
            glm::vec4(m.specular, m.specularExponent),
            glm::vec4(m.reflectivity, m.ior, m.opacity, m.fresnel ? 1.0f : 0.0f),
            glm::vec4(m.textureTiling, m.textureOffset),
            glm::ivec4(m.diffuseTexture, m.normalTexture, 0, 0)};
}

}  // namespace

bool GpuScene::castsShadow(const Material& m) {
    const glm::vec3 t = occluderTransmittance(m);
    return (t.r + t.g + t.b) / 3.0f < 0.5f;
}

GpuScene::GpuScene(std::shared_ptr<VulkanDevice> device, const Scene& scene, DeformedMeshCache* deformedMeshes)
    : device_(std::move(device)), scene_(scene), textures_(*device_, scene) {
    if (!deformedMeshes) ownDeformedMeshes_ = std::make_unique<DeformedMeshCache>(scene);
    deformedMeshes_ = deformedMeshes ? deformedMeshes : ownDeformedMeshes_.get();
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<std::int32_t> meshFirstIndex(scene.meshes.size());
    meshVertexOffset_.resize(scene.meshes.size());
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& m = scene.meshes[i];
        meshVertexOffset_[i] = static_cast<std::int32_t>(vertices.size());
        meshFirstIndex[i] = static_cast<std::int32_t>(indices.size());
        for (std::size_t v = 0; v < m.positions.size(); ++v) vertices.push_back(packVertex(m, v, nullptr));
        for (const glm::uvec3& t : m.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
    }
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o) {
        const std::size_t first = draws_.size();
        for (std::uint32_t mesh : scene.objects[o].meshes) {
            const Mesh& m = scene.meshes[mesh];
            if (m.triangles.empty()) continue;
            MeshDraw d;
            d.object = o;
            d.mesh = mesh;
            d.material = m.material;
            d.firstIndex = static_cast<std::uint32_t>(meshFirstIndex[mesh]);
            d.indexCount = static_cast<std::uint32_t>(3 * m.triangles.size());
            d.vertexOffset = meshVertexOffset_[mesh];
            d.flags = (!m.uvs.empty() && !m.tangents.empty()) ? kHasTangentSpace : 0u;
            d.castsShadow = castsShadow(scene.materials[m.material]);
            d.localBounds = scene.objects[o].deformation.envelope(m.bounds());
            draws_.push_back(d);
        }
        objectDraws_.push_back({first, draws_.size()});
    }
    worldBounds_.resize(draws_.size());

    const VulkanDevice& dev = *device_;
    bool anyDeforming = false;
    for (const SceneObject& o : scene.objects) anyDeforming |= o.isDeforming();
    if (anyDeforming) {
        // Deforming meshes are rewritten every frame (setTime): mapped, like the draw records.
        vertices_ = GpuBuffer(dev, std::max<std::size_t>(1, vertices.size()) * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                              GpuBuffer::Memory::DeviceLocalHostVisible);
        vertices_.write(vertices.data(), vertices.size() * sizeof(Vertex));
    } else {
        vertices_ = GpuBuffer::withData(dev, vertices.data(), vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    }
    indices_ = GpuBuffer::withData(dev, indices.data(), indices.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    const VkDeviceSize align = std::max<VkDeviceSize>(16, dev.properties().limits.minUniformBufferOffsetAlignment);
    recordStride_ = (sizeof(DrawRecord) + align - 1) / align * align;
    drawRecords_ = GpuBuffer(dev, std::max<std::size_t>(1, draws_.size()) * recordStride_, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                             GpuBuffer::Memory::DeviceLocalHostVisible);
    for (std::size_t d = 0; d < draws_.size(); ++d) {
        const MaterialData m = materialData(scene.materials[draws_[d].material]);
        drawRecords_.write(&m, sizeof m, d * recordStride_ + offsetof(DrawRecord, material));
    }

    const VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    descriptors_ = DescriptorSet(dev, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1, both, nullptr}});
    descriptors_.writeBuffer(0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, drawRecords_.buffer(), 0, sizeof(DrawRecord));
    // One set per material rather than one array of every texture: indexing a sampler array by a
    // material index needs shaderSampledImageArrayDynamicIndexing, which lavapipe lacks.
    const auto materialCount = static_cast<std::uint32_t>(std::max<std::size_t>(1, scene.materials.size()));
    materialTextures_ = DescriptorSet(dev,
                                      {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
                                       {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr}},
                                      materialCount);
    for (std::uint32_t i = 0; i < materialCount; ++i) {
        const Material* m = i < scene.materials.size() ? &scene.materials[i] : nullptr;
        materialTextures_.writeImages(0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, {textures_.texture(m ? m->diffuseTexture : kNoTexture)}, i);
        materialTextures_.writeImages(1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, {textures_.texture(m ? m->normalTexture : kNoTexture)}, i);
    }
    setTime(0.0);
}

bool GpuScene::setTime(double time) {
    bool moved = !timeSet_;
    for (std::size_t o = 0; o < scene_.objects.size(); ++o) {
        const SceneObject& object = scene_.objects[o];
        if (object.isDeforming()) writeDeformedVertices(o, time);
        // Deforming objects' local bounds are their envelopes: only a moving object's placement changes.
        if (!timeSet_ || object.isAnimated()) writePlacement(o, time);
        moved |= object.isDynamic();
    }
    timeSet_ = true;
    return moved;
}

void GpuScene::writePlacement(std::size_t object, double time) {
    const glm::mat4 model = scene_.objects[object].worldMatrix(time);
    const ObjectData data{model, glm::mat4(normalMatrix(model))};
    for (std::size_t d = objectDraws_[object].first; d < objectDraws_[object].second; ++d) {
        drawRecords_.write(&data, sizeof data, d * recordStride_ + offsetof(DrawRecord, object));
        worldBounds_[d] = draws_[d].localBounds.transformed(model);
    }
}

void GpuScene::writeDeformedVertices(std::size_t object, double time) {
    const std::vector<std::uint32_t>& meshes = scene_.objects[object].meshes;
    const std::vector<DeformedVertices>& deformed = deformedMeshes_->vertices(object, time, DeformedMeshCache::kRasterizer);
    std::vector<Vertex> packed;
    for (std::size_t k = 0; k < meshes.size(); ++k) {
        const Mesh& m = scene_.meshes[meshes[k]];
        packed.resize(m.positions.size());
        for (std::size_t v = 0; v < packed.size(); ++v) packed[v] = packVertex(m, v, &deformed[k]);
        vertices_.write(packed.data(), packed.size() * sizeof(Vertex), static_cast<VkDeviceSize>(meshVertexOffset_[meshes[k]]) * sizeof(Vertex));
    }
}

Aabb GpuScene::bounds() const {
    Aabb b;
    for (const Aabb& w : worldBounds_) b.extend(w);
    return b;
}

std::vector<VkVertexInputBindingDescription> GpuScene::vertexBindings() { return {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}}; }

std::vector<VkVertexInputAttributeDescription> GpuScene::vertexAttributes(bool positionOnly) {
    std::vector<VkVertexInputAttributeDescription> a = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)}};
    if (positionOnly) return a;
    a.push_back({1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)});
    a.push_back({2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)});
    a.push_back({3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangent)});
    return a;
}

void GpuScene::bind(VkCommandBuffer cb) const {
    VkBuffer vb = vertices_.buffer();
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cb, 0, 1, &vb, &offset);
    vkCmdBindIndexBuffer(cb, indices_.buffer(), 0, VK_INDEX_TYPE_UINT32);
}

void GpuScene::recordDraw(VkCommandBuffer cb, VkPipelineLayout layout, const glm::mat4& viewProj, std::size_t draw, bool textures) const {
    const MeshDraw& d = draws_[draw];
    const auto recordOffset = static_cast<std::uint32_t>(draw * recordStride_);
    VkDescriptorSet set = descriptors_.set();
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 1, &recordOffset);
    if (textures) {
        VkDescriptorSet t = materialTextures_.set(d.material);
        vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &t, 0, nullptr);
    }
    const DrawConstants c{viewProj, d.object, d.flags};
    vkCmdPushConstants(cb, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof c, &c);
    vkCmdDrawIndexed(cb, d.indexCount, 1, d.firstIndex, d.vertexOffset, 0);
}

std::size_t GpuScene::recordDraws(VkCommandBuffer cb, VkPipelineLayout layout, const glm::mat4& viewProj, bool textures,
                                  const std::function<bool(const MeshDraw&)>& include) const {
    const Frustum frustum(viewProj);
    std::size_t n = 0;
    for (std::size_t i = 0; i < draws_.size(); ++i) {
        if (include && !include(draws_[i])) continue;
        if (!frustum.intersects(worldBounds_[i])) continue;
        recordDraw(cb, layout, viewProj, i, textures);
        ++n;
    }
    return n;
}

}  // namespace hybridlab
