#pragma once
// The headless Vulkan 1.3 device of the raster core: no window, no swapchain, offscreen images
// only. It prefers a discrete GPU, then an integrated one, then a CPU device (Mesa lavapipe, the
// software rasteriser every machine of the project has); HYBRIDLAB_VULKAN_DEVICE=<part of a device
// name> picks by name (the tests pick lavapipe, "llvmpipe", whose results they were calibrated on).
// Validation layers are on in debug builds (or with HYBRIDLAB_VULKAN_VALIDATION=1) when installed.
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "common/raster/memory_use.h"
#include "common/raster/vk_unique.h"

namespace hybridlab {

// What a device is asked for beyond the raster core. Ray tracing enables
// VK_KHR_acceleration_structure, VK_KHR_ray_tracing_pipeline and what they need (buffer device
// addresses, deferred host operations, descriptor indexing) only on the device that asks: the
// raster techniques keep running on drivers without them.
struct DeviceFeatures {
    bool rayTracing = false;
    bool operator<(const DeviceFeatures& o) const { return rayTracing < o.rayTracing; }
};

// What the process asked of its Vulkan devices besides the passes' own work, counted since it
// started over every device (VulkanDevice::workSoFar()): a frame's share is the difference across
// it (techniques/device_frame_work.h). Submissions are queue submissions, each waited for with a
// fence (a CPU round trip); read-back bytes are what the host read of memory the device wrote
// (GpuBuffer::readBack, and query results); allocations are the objects a pass creates for its
// data: device memory (one a buffer or image), descriptor sets and command buffers. A frame's
// diagnostics (debug images, statistics), read after its timed stages inside a
// VulkanDevice::Diagnostics scope, count apart: they are not the technique's work.
struct DeviceWork {
    std::uint64_t submissions = 0;
    std::uint64_t readBackBytes = 0;
    std::uint64_t allocations = 0;
    std::uint64_t diagnosticSubmissions = 0;
    std::uint64_t diagnosticReadBackBytes = 0;

    DeviceWork operator-(const DeviceWork& since) const {
        return {submissions - since.submissions, readBackBytes - since.readBackBytes, allocations - since.allocations,
                diagnosticSubmissions - since.diagnosticSubmissions, diagnosticReadBackBytes - since.diagnosticReadBackBytes};
    }
    bool operator==(const DeviceWork&) const = default;
};

// The ray-tracing entry points, which the loader does not export: looked up on the device.
struct RayTracingFunctions {
    PFN_vkCreateAccelerationStructureKHR createAccelerationStructure = nullptr;
    PFN_vkDestroyAccelerationStructureKHR destroyAccelerationStructure = nullptr;
    PFN_vkGetAccelerationStructureBuildSizesKHR getAccelerationStructureBuildSizes = nullptr;
    PFN_vkGetAccelerationStructureDeviceAddressKHR getAccelerationStructureDeviceAddress = nullptr;
    PFN_vkCmdBuildAccelerationStructuresKHR cmdBuildAccelerationStructures = nullptr;
    PFN_vkCreateRayTracingPipelinesKHR createRayTracingPipelines = nullptr;
    PFN_vkGetRayTracingShaderGroupHandlesKHR getRayTracingShaderGroupHandles = nullptr;
    PFN_vkCmdTraceRaysKHR cmdTraceRays = nullptr;
    PFN_vkCmdTraceRaysIndirectKHR cmdTraceRaysIndirect = nullptr;  // where traceRaysIndirect()
};

class VulkanDevice {
public:
    // The process-wide device with `features`, created at first call. Throws VulkanUnavailable
    // (with the reason) when there is no Vulkan loader, no 1.3 device, or the device lacks what the
    // raster core (and the features) need; later calls throw the same error again. A device with
    // ray tracing is a second VkDevice on the same physical device.
    static std::shared_ptr<VulkanDevice> shared(DeviceFeatures features = {});

    // The device extensions that `features` need and `physicalDevice` lacks (empty: none). The
    // environment variable HYBRIDLAB_VULKAN_HIDE_EXTENSIONS (comma-separated names) hides
    // extensions from this check, so that a test can play a driver without them.
    static std::vector<std::string> missingExtensions(VkPhysicalDevice physicalDevice, DeviceFeatures features);

    ~VulkanDevice();
    VulkanDevice(const VulkanDevice&) = delete;
    VulkanDevice& operator=(const VulkanDevice&) = delete;

    VkDevice device() const { return device_; }
    VkPhysicalDevice physicalDevice() const { return physical_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    std::string name() const { return properties_.deviceName; }
    bool isLavapipe() const { return lavapipe_; }
    VkPhysicalDeviceType type() const { return properties_.deviceType; }
    // Whether pipeline-statistics queries are enabled (the device supports them; lavapipe does).
    bool pipelineStatistics() const { return pipelineStatistics_; }
    // Ray-tracing devices: launches whose size the device writes (vkCmdTraceRaysIndirectKHR).
    bool traceRaysIndirect() const { return traceRaysIndirect_; }
    // The driver's name and version text, e.g. "llvmpipe, Mesa 25.0.7 (LLVM 15.0.6)".
    std::string driver() const { return std::string(driver_.driverName) + ", " + driver_.driverInfo; }
    const DeviceFeatures& features() const { return features_; }
    // Ray-tracing devices only.
    const RayTracingFunctions& rayTracing() const { return rayTracing_; }
    const VkPhysicalDeviceRayTracingPipelinePropertiesKHR& rayTracingProperties() const { return rayTracingProperties_; }
    // The device's largest memory heap that is device-local, in bytes (what a scene must fit in).
    VkDeviceSize deviceLocalBytes() const;
    float maxAnisotropy() const { return properties_.limits.maxSamplerAnisotropy; }
    // Nanoseconds per timestamp tick.
    double timestampPeriod() const { return properties_.limits.timestampPeriod; }

    const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memory_; }
    // Memory for a resource with requirements `req`, of the first type memoryTypeCandidates() gives
    // for `use` whose allocation succeeds; its type's property flags in `properties` where given.
    // `what` names it in errors. `deviceAddress`: the memory of a buffer whose device address
    // shaders or builds take.
    using MemoryUse = hybridlab::MemoryUse;
    UniqueDeviceMemory allocate(const VkMemoryRequirements& req, MemoryUse use, const char* what, bool deviceAddress = false,
                                VkMemoryPropertyFlags* properties = nullptr) const;

    // Throws VulkanError naming the format and what it is needed for unless the format supports
    // `features` with optimal tiling.
    void requireFormat(VkFormat format, VkFormatFeatureFlags features, const char* purpose) const;

    // Records commands into a one-time command buffer, submits it and waits for it. The command
    // buffers are the device's, reused from call to call (one for each level of calls made while
    // recording another's): none is allocated in a steady state.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;
    // Submits an already recorded command buffer and waits for it.
    void submitAndWait(VkCommandBuffer commands) const;

    // The work every device of the process was asked for so far (DeviceWork), and the counts of
    // what is not counted where it happens here: `bytes` the host read back, `objects` allocated.
    static DeviceWork workSoFar();
    static void countReadBack(std::uint64_t bytes);
    static void countAllocations(std::uint64_t objects);
    // While one lives, this thread's submissions and read-back count as diagnostics (DeviceWork).
    class Diagnostics {
    public:
        Diagnostics();
        ~Diagnostics();
        Diagnostics(const Diagnostics&) = delete;
        Diagnostics& operator=(const Diagnostics&) = delete;
    };

private:
    explicit VulkanDevice(DeviceFeatures features) : features_(features) {}
    // create() runs these in order; each throws VulkanUnavailable saying what is missing.
    void create();
    void createInstance();
    void choosePhysicalDevice();
    std::vector<const char*> rayTracingExtensionsToEnable();
    void createLogicalDevice(const std::vector<const char*>& extensions);
    void loadRayTracingFunctions();
    void createCommandPoolAndFence();

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::uint32_t queueFamily_ = 0;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    VkPhysicalDeviceDriverProperties driver_{};
    bool lavapipe_ = false;
    bool pipelineStatistics_ = false;
    bool traceRaysIndirect_ = false;
    DeviceFeatures features_;
    RayTracingFunctions rayTracing_;
    VkPhysicalDeviceRayTracingPipelinePropertiesKHR rayTracingProperties_{};
    UniqueCommandPool pool_;
    UniqueFence fence_;
    mutable std::recursive_mutex submitMutex_;  // the queue, fence and pool: one submission at a time
    mutable std::vector<VkCommandBuffer> commandBuffers_;  // submitAndWait(record)'s, by depth; freed with the pool
    mutable std::size_t recordingDepth_ = 0;
};

// Runs `release` (a lambda without captures) once at exit, from a handler registered at the first
// call. Called once a device exists, that is after the Vulkan driver and layers registered their
// own exit handlers, it runs before them (exit handlers run in reverse order): a process-wide
// cache of Vulkan objects released by a static destructor instead would call into a driver or
// layer already torn down (the validation layer here, NVIDIA's driver on an H200).
template <class Release>
void releaseBeforeTheDriverAtExit(Release) {
    static const bool registered = std::atexit([] { Release{}(); }) == 0;
    (void)registered;
}

}  // namespace hybridlab
