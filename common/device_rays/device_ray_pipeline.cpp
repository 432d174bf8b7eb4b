#include "common/device_rays/device_ray_pipeline.h"

#include <cstring>
#include <map>
#include <mutex>
#include <tuple>

#include "common/raster/vulkan_error.h"

namespace hybridlab {

using namespace device_rays;

namespace {

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

// GPU stages of a launch: the classification, the trace, and the pass after it. Timestamps only: on lavapipe (Mesa
// 25.0.7) a second stage's pipeline-statistics query after vkCmdTraceRaysKHR crashes the queue thread.
constexpr std::uint32_t kLaunchStages = 3;

// The shader stages: ray generation, radiance closest hit and miss, shadow miss and any hit.
enum Stage : std::uint32_t { kRaygen, kRadianceHit, kRadianceMiss, kShadowMiss, kShadowAnyHit, kStageCount };

std::vector<VkDescriptorSetLayoutBinding> descriptorBindings(std::uint32_t textureCount) {
    // Compute too: a compacted launch's classification pass reads the frame and writes the output.
    const VkShaderStageFlags all = VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_ANY_HIT_BIT_KHR |
                                   VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR | VK_SHADER_STAGE_MISS_BIT_KHR | VK_SHADER_STAGE_COMPUTE_BIT;
    const VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, sampler = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    return {{0, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1, all, nullptr},
                                       {1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, all, nullptr},
                                       {2, storage, 1, all, nullptr},
                                       {3, storage, 1, all, nullptr},
                                       {4, storage, 1, all, nullptr},
                                       {5, storage, 1, all, nullptr},
                                       {6, storage, 1, all, nullptr},
                                       {7, storage, 1, all, nullptr},
                                       {8, storage, 1, all, nullptr},
                                       {9, sampler, 1, all, nullptr},
                                       {10, sampler, textureCount, all, nullptr},
                                       {11, storage, 1, all, nullptr}};
}

// Compiles the pipeline and its binding table. Slow (lavapipe compiles the shaders into one
// program with LLVM: about 10 s of CPU time), hence compiled once per process and shared.
std::shared_ptr<const CompiledRayPipeline> compile(const VulkanDevice& dev, const std::string& raygenShader, std::uint32_t textureCount,
                                                   const std::vector<VkDescriptorSetLayoutBinding>& inputs) {
    auto program = std::make_shared<CompiledRayPipeline>();
    program->setLayout = DescriptorSet(dev, descriptorBindings(textureCount));
    std::vector<VkDescriptorSetLayout> sets = {program->setLayout.layout()};
    if (!inputs.empty()) {
        program->inputLayout = DescriptorSet(dev, inputs);
        sets.push_back(program->inputLayout.layout());
    }
    program->layout = createPipelineLayout(dev, sets, 0);

    const std::string shaders[kStageCount] = {raygenShader, "device_radiance.rchit", "device_radiance.rmiss", "device_shadow.rmiss",
                                        "device_shadow.rahit"};
    const VkShaderStageFlagBits stages[kStageCount] = {VK_SHADER_STAGE_RAYGEN_BIT_KHR, VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR,
                                                       VK_SHADER_STAGE_MISS_BIT_KHR, VK_SHADER_STAGE_MISS_BIT_KHR,
                                                       VK_SHADER_STAGE_ANY_HIT_BIT_KHR};
    std::vector<UniqueShaderModule> modules;
    std::vector<VkPipelineShaderStageCreateInfo> stageInfos;
    for (std::uint32_t i = 0; i < kStageCount; ++i) {
        modules.push_back(createShaderModule(dev, shaders[i]));
        VkPipelineShaderStageCreateInfo si{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        si.stage = stages[i];
        si.module = modules.back();
        si.pName = "main";
        stageInfos.push_back(si);
    }
    auto group = [](VkRayTracingShaderGroupTypeKHR type, std::uint32_t general, std::uint32_t closestHit, std::uint32_t anyHit) {
        VkRayTracingShaderGroupCreateInfoKHR g{VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
        g.type = type;
        g.generalShader = general;
        g.closestHitShader = closestHit;
        g.anyHitShader = anyHit;
        g.intersectionShader = VK_SHADER_UNUSED_KHR;
        return g;
    };
    const std::uint32_t unused = VK_SHADER_UNUSED_KHR;
    const VkRayTracingShaderGroupTypeKHR general = VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR,
                                         triangles = VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
    // Binding-table order: raygen | radiance miss, shadow miss | radiance hit, shadow hit.
    const std::vector<VkRayTracingShaderGroupCreateInfoKHR> groups = {
        group(general, kRaygen, unused, unused),           group(general, kRadianceMiss, unused, unused),
        group(general, kShadowMiss, unused, unused),       group(triangles, unused, kRadianceHit, unused),
        group(triangles, unused, unused, kShadowAnyHit)};
    VkRayTracingPipelineCreateInfoKHR pci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
    pci.stageCount = static_cast<std::uint32_t>(stageInfos.size());
    pci.pStages = stageInfos.data();
    pci.groupCount = static_cast<std::uint32_t>(groups.size());
    pci.pGroups = groups.data();
    pci.maxPipelineRayRecursionDepth = 1;  // rays are traced from the ray-generation shader only
    pci.layout = program->layout;
    VkPipeline pipeline;
    checkVk(dev.rayTracing().createRayTracingPipelines(dev.device(), VK_NULL_HANDLE, VK_NULL_HANDLE, 1, &pci, nullptr, &pipeline),
            "creating the ray-tracing pipeline");
    program->pipeline = UniquePipeline(dev.device(), pipeline);

    // The shader binding table: one record per group, each region aligned to the base alignment.
    const auto& rt = dev.rayTracingProperties();
    const std::uint32_t handleSize = rt.shaderGroupHandleSize;
    const VkDeviceSize stride = alignUp(handleSize, rt.shaderGroupHandleAlignment);
    const VkDeviceSize base = rt.shaderGroupBaseAlignment;
    std::vector<std::uint8_t> handles(groups.size() * handleSize);
    checkVk(dev.rayTracing().getRayTracingShaderGroupHandles(dev.device(), program->pipeline, 0, static_cast<std::uint32_t>(groups.size()),
                                                             handles.size(), handles.data()),
            "reading shader group handles");
    const VkDeviceSize raygenOffset = 0, missOffset = alignUp(stride, base), hitOffset = missOffset + alignUp(2 * stride, base);
    const VkDeviceSize tableSize = hitOffset + 2 * stride;
    std::vector<std::uint8_t> table(tableSize, 0);
    std::memcpy(&table[raygenOffset], &handles[0], handleSize);
    std::memcpy(&table[missOffset], &handles[1 * handleSize], handleSize);
    std::memcpy(&table[missOffset + stride], &handles[2 * handleSize], handleSize);
    std::memcpy(&table[hitOffset], &handles[3 * handleSize], handleSize);
    std::memcpy(&table[hitOffset + stride], &handles[4 * handleSize], handleSize);
    // The table's start must meet the base alignment too: allocate one alignment more and offset.
    // Device-local: every ray reads its records.
    program->bindingTable = GpuBuffer(dev, tableSize + base,
                                      VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                          VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      GpuBuffer::Memory::DeviceLocal);
    const VkDeviceAddress address = program->bindingTable.deviceAddress(dev);
    const VkDeviceSize shift = alignUp(address, base) - address;
    program->bindingTable.upload(dev, table.data(), tableSize, shift);
    program->raygen = {address + shift + raygenOffset, stride, stride};
    program->miss = {address + shift + missOffset, stride, 2 * stride};
    program->hit = {address + shift + hitOffset, stride, 2 * stride};
    return program;
}

}  // namespace

DeviceRayPipeline::DeviceRayPipeline(const DeviceRayScene& scene, const std::string& raygenShader,
                                     const std::vector<VkDescriptorSetLayoutBinding>& inputs)
    : scene_(scene), device_(scene.device()), timer_(scene.device(), kLaunchStages, /*statistics=*/false) {
    const VulkanDevice& dev = device_;
    const std::uint32_t textureCount = std::max<std::uint32_t>(1, static_cast<std::uint32_t>(scene.scene().textures.size()));
    {
        // Identically declared set layouts are compatible: this scene's sets bind to the shared
        // pipeline (a ray-generation shader declares one set 1, so its name keys it).
        static std::mutex mutex;
        // Released as VulkanDevice::shared()'s devices are, by a handler registered after theirs:
        // the pipelines go first.
        static auto& compiled = *new std::map<std::tuple<VkDevice, std::string, std::uint32_t>, std::shared_ptr<const CompiledRayPipeline>>;
        releaseBeforeTheDriverAtExit([] {
            std::lock_guard exitLock(mutex);
            compiled.clear();
        });
        std::lock_guard lock(mutex);
        auto& entry = compiled[{dev.device(), raygenShader, textureCount}];
        if (!entry) entry = compile(dev, raygenShader, textureCount, inputs);
        program_ = entry;
    }
    const VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, sampler = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    descriptors_ = DescriptorSet(dev, descriptorBindings(textureCount));
    if (!inputs.empty()) inputs_ = DescriptorSet(dev, inputs);
    frame_ = GpuBuffer(dev, sizeof(DeviceFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, GpuBuffer::Memory::DeviceLocalHostVisible);
    counters_ = GpuBuffer(dev, kRayCounterCount * sizeof(std::uint32_t),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          GpuBuffer::Memory::DeviceLocal);
    countersOnHost_ = GpuBuffer(dev, counters_.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuBuffer::Memory::HostVisible);

    VkWriteDescriptorSetAccelerationStructureKHR as{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
    VkAccelerationStructureKHR topLevel = scene.topLevel();
    as.accelerationStructureCount = 1;
    as.pAccelerationStructures = &topLevel;
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, &as};
    w.dstSet = descriptors_.set();
    w.dstBinding = 0;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
    vkUpdateDescriptorSets(dev.device(), 1, &w, 0, nullptr);
    descriptors_.writeBuffer(1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, frame_.buffer());
    descriptors_.writeBuffer(2, storage, scene.materials().buffer());
    descriptors_.writeBuffer(3, storage, scene.lights().buffer());
    descriptors_.writeBuffer(4, storage, scene.instances().buffer());
    descriptors_.writeBuffer(5, storage, scene.vertices().buffer());
    descriptors_.writeBuffer(6, storage, scene.indices().buffer());
    descriptors_.writeBuffer(7, storage, counters_.buffer());
    descriptors_.writeImages(9, sampler, {scene.textures().sky()});
    std::vector<VkDescriptorImageInfo> textures;
    for (std::uint32_t i = 0; i < textureCount; ++i) {
        textures.push_back(scene.textures().texture(scene.scene().textures.empty() ? kNoTexture : static_cast<std::int32_t>(i)));
    }
    descriptors_.writeImages(10, sampler, textures);
    output(sizeof(glm::vec4));
    setReplayRays(GpuBuffer(dev, sizeof(DeviceRay), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, GpuBuffer::Memory::DeviceLocal));
}

const GpuBuffer& DeviceRayPipeline::output(VkDeviceSize bytes) {
    if (!output_.valid() || output_.size() != bytes) {
        output_ = GpuBuffer(device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                            GpuBuffer::Memory::DeviceLocal);
        outputOnHost_ = GpuBuffer(device_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, GpuBuffer::Memory::HostVisible);
        descriptors_.writeBuffer(8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, output_.buffer());
    }
    return output_;
}

std::vector<std::pair<std::string, VkMemoryPropertyFlags>> DeviceRayPipeline::bufferMemory() const {
    return {{"vertices", scene_.vertices().memoryProperties()},
            {"indices", scene_.indices().memoryProperties()},
            {"materials", scene_.materials().memoryProperties()},
            {"lights", scene_.lights().memoryProperties()},
            {"instances", scene_.instances().memoryProperties()},
            {"instance descriptors", scene_.instanceDescriptors().memoryProperties()},
            {"shader binding table", program_->bindingTable.memoryProperties()},
            {"frame", frame_.memoryProperties()},
            {"replayed rays", replay_.memoryProperties()},
            {"counters", counters_.memoryProperties()},
            {"output", output_.memoryProperties()}};
}

void DeviceRayPipeline::setReplayRays(GpuBuffer rays) {
    replay_ = std::move(rays);
    descriptors_.writeBuffer(11, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, replay_.buffer());
}

void DeviceRayPipeline::bindSets(VkCommandBuffer cb, VkPipelineBindPoint point) const {
    const VkDescriptorSet sets[2] = {descriptors_.set(), inputs_.layout() != VK_NULL_HANDLE ? inputs_.set() : VK_NULL_HANDLE};
    vkCmdBindDescriptorSets(cb, point, program_->layout, 0, sets[1] ? 2 : 1, sets, 0, nullptr);
}

void DeviceRayPipeline::record(VkCommandBuffer cb, const RayLaunch& launch) {
    const VulkanDevice& dev = device_;
    timer_.reset(cb);
    vkCmdFillBuffer(cb, counters_.buffer(), 0, VK_WHOLE_SIZE, 0);
    if (launch.before) launch.before(cb);
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, program_->pipeline);
    bindSets(cb, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR);
    // The rasterizer's targets the shaders may read were written earlier on this queue (in this
    // command buffer or an earlier one); the counters were zeroed above.
    VkMemoryBarrier inputs{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_MEMORY_WRITE_BIT,
                           VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &inputs, 0, nullptr, 0,
                         nullptr);
    if (launch.classify) {
        timer_.begin(cb, launch.classifyStage);
        launch.classify(cb);
        timer_.end(cb);
        // The list and the texels it left out, then the launch's size, read by the trace.
        VkMemoryBarrier listed{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                               VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                             VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR, 0, 1, &listed, 0, nullptr,
                             0, nullptr);
    }
    timer_.begin(cb, launch.stage);
    if (launch.classify) {
        dev.rayTracing().cmdTraceRaysIndirect(cb, &program_->raygen, &program_->miss, &program_->hit, &program_->callable, launch.indirect);
    } else {
        dev.rayTracing().cmdTraceRays(cb, &program_->raygen, &program_->miss, &program_->hit, &program_->callable, launch.width,
                                      launch.height, 1);
    }
    timer_.end(cb);
    // The trace's writes, read by the pass after it and by the copies to the host.
    VkPipelineStageFlags readers = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    if (launch.after) {
        readers |= VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
        barrier.dstAccessMask |= VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    }
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR, readers, 0, 1, &barrier, 0, nullptr, 0, nullptr);
    if (launch.after) {
        timer_.begin(cb, launch.afterStage);
        launch.after(cb);
        timer_.end(cb);
        VkMemoryBarrier done{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT};
        vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &done, 0, nullptr, 0, nullptr);
    }
    // What the host reads: the counters, the image, and the caller's own.
    const VkBufferCopy counters{0, 0, counters_.size()};
    vkCmdCopyBuffer(cb, counters_.buffer(), countersOnHost_.buffer(), 1, &counters);
    if (launch.readOutput) {
        const VkBufferCopy image{0, 0, output_.size()};
        vkCmdCopyBuffer(cb, output_.buffer(), outputOnHost_.buffer(), 1, &image);
    }
    if (launch.readBack) launch.readBack(cb);
    VkMemoryBarrier copied{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &copied, 0, nullptr, 0, nullptr);
}

DeviceLaunchCounts DeviceRayPipeline::launch(const RayLaunch& launch) {
    device_.submitAndWait([&](VkCommandBuffer cb) { record(cb, launch); });
    return counts();
}

DeviceLaunchCounts DeviceRayPipeline::counts() const {
    std::array<std::uint32_t, kRayCounterCount> c;
    std::memcpy(c.data(), countersOnHost_.readBack(sizeof(c)), sizeof(c));
    DeviceLaunchCounts counts;
    counts.rays.primary = c[0];
    counts.rays.shadow = c[1];
    counts.rays.reflection = c[2];
    counts.rays.refraction = c[3];
    counts.rays.mediumErrors = c[4];
    counts.invocations = {c[kLaunchedInvocations], c[kTracingInvocations]};
    return counts;
}

}  // namespace hybridlab
