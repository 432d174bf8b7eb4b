// Where the buffers the device's rays read every frame live (DeviceRayPipeline::bufferMemory):
// in device-local memory, and what the host rewrites each frame (the instances, their
// acceleration-structure descriptors, the frame's uniforms) also host-visible, where the device
// has such memory; in the first memory type memoryTypeCandidates() gives, on any device. On
// lavapipe every type is both; on a GPU host-visible memory alone is read across PCIe.
#include <string>

#include <gtest/gtest.h>

#include "common/device_rays/device_ray_pipeline.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "tests/support/raster_test_support.h"

namespace hybridlab {
namespace {

TEST(DeviceRayMemory, TheRaysReadDeviceLocalMemoryAndTheRewrittenBuffersAreMapped) {
    REQUIRE_RAY_TRACING_DEVICE();
    const Scene scene = loadSceneFile(findSceneFile("teapots-deforming-5"));
    DeformedMeshCache deformed(scene);
    auto device = VulkanDevice::shared({.rayTracing = true});
    DeviceRayScene rays(device, scene, deformed);
    DeviceRayPipeline pipeline(rays, "device_whitted.rgen");
    const VkPhysicalDeviceMemoryProperties& memory = device->memoryProperties();
    auto offered = [&](MemoryUse use) {
        const auto types = memoryTypeCandidates(memory, ~0u, use);
        return types.empty() ? VkMemoryPropertyFlags(0) : memory.memoryTypes[types.front()].propertyFlags;
    };
    const VkMemoryPropertyFlags local = offered(MemoryUse::DeviceLocal), rewritten = offered(MemoryUse::DeviceLocalHostVisible);
    ASSERT_TRUE(local & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) << device->name() << " offers no device-local memory";
    int buffers = 0;
    for (const auto& [name, flags] : pipeline.bufferMemory()) {
        SCOPED_TRACE(name);
        ++buffers;
        const bool hostWritten = name == "instances" || name == "instance descriptors" || name == "frame";
        EXPECT_EQ(flags, hostWritten ? rewritten : local);
        EXPECT_TRUE(flags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        if (hostWritten) {
            EXPECT_TRUE(flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT);
        }
    }
    EXPECT_EQ(buffers, 11);
}

}  // namespace
}  // namespace hybridlab
