// memoryTypeCandidates on the memory tables of the devices the project meets: lavapipe (one type
// with every bit), an NVIDIA GPU with and without resizable BAR (a device-local host-visible type,
// or none), an AMD GPU whose BAR type comes first. Static data goes to the GPU's own memory and
// not to the small BAR heap; what the host rewrites each frame to the BAR where there is one, else
// to uncached system memory; read-back to cached system memory.
#include <cstdint>
#include <initializer_list>
#include <vector>

#include <gtest/gtest.h>

#include "common/raster/memory_use.h"

namespace hybridlab {
namespace {

constexpr VkMemoryPropertyFlags kLocal = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
constexpr VkMemoryPropertyFlags kHost = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
constexpr VkMemoryPropertyFlags kCached = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
constexpr std::uint32_t kAll = ~0u;

VkPhysicalDeviceMemoryProperties table(std::initializer_list<VkMemoryPropertyFlags> types) {
    VkPhysicalDeviceMemoryProperties m{};
    for (VkMemoryPropertyFlags flags : types) m.memoryTypes[m.memoryTypeCount++].propertyFlags = flags;
    return m;
}

using Types = std::vector<std::uint32_t>;

TEST(MemoryUse, LavapipesOneTypeServesEveryUse) {
    const auto m = table({kLocal | kHost | kCached});
    for (MemoryUse use : {MemoryUse::DeviceLocal, MemoryUse::HostVisible, MemoryUse::DeviceLocalHostVisible})
        EXPECT_EQ(memoryTypeCandidates(m, kAll, use), Types({0}));
}

TEST(MemoryUse, NvidiaWithABarHeapPutsRewrittenBuffersThereAndStaticOnesBeside) {
    // An NVIDIA discrete GPU's table: 0 no flags, 1 device-local, 2 and 3 system memory
    // (uncached, cached), 4 the BAR (device-local, host-visible).
    const auto m = table({0, kLocal, kHost, kHost | kCached, kLocal | kHost});
    EXPECT_EQ(memoryTypeCandidates(m, kAll, MemoryUse::DeviceLocal), Types({1, 4}));
    EXPECT_EQ(memoryTypeCandidates(m, kAll, MemoryUse::HostVisible), Types({3, 2, 4}));
    EXPECT_EQ(memoryTypeCandidates(m, kAll, MemoryUse::DeviceLocalHostVisible), Types({4, 2, 3}));
    // A resource that cannot live in the BAR falls back to uncached system memory.
    EXPECT_EQ(memoryTypeCandidates(m, 0b01110, MemoryUse::DeviceLocalHostVisible), Types({2, 3}));
}

TEST(MemoryUse, AGpuWithoutABarWritesPerFrameBuffersToUncachedSystemMemory) {
    const auto m = table({kLocal, kHost | kCached, kHost});
    EXPECT_EQ(memoryTypeCandidates(m, kAll, MemoryUse::DeviceLocal), Types({0}));
    EXPECT_EQ(memoryTypeCandidates(m, kAll, MemoryUse::HostVisible), Types({1, 2}));
    EXPECT_EQ(memoryTypeCandidates(m, kAll, MemoryUse::DeviceLocalHostVisible), Types({2, 1}));
}

TEST(MemoryUse, ABarTypeListedFirstIsLeftForWhatTheHostRewrites) {
    // AMD lists its BAR type before the plain device-local one on some drivers.
    const auto m = table({kLocal | kHost, kLocal, kHost | kCached});
    EXPECT_EQ(memoryTypeCandidates(m, kAll, MemoryUse::DeviceLocal), Types({1, 0}));
    EXPECT_EQ(memoryTypeCandidates(m, kAll, MemoryUse::DeviceLocalHostVisible), Types({0, 2}));
    EXPECT_TRUE(memoryTypeCandidates(m, 0b100, MemoryUse::DeviceLocal).empty());
}

}  // namespace
}  // namespace hybridlab
