#include "common/raster/vulkan_device.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <atomic>
#include <map>
#include <optional>
#include <type_traits>
#include <vector>

#include "common/raster/vulkan_error.h"

namespace hybridlab {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// DeviceWork's counts, over every device of the process.
std::atomic<std::uint64_t> submissionCount{0}, readBackByteCount{0}, allocationCount{0}, diagnosticSubmissionCount{0},
    diagnosticReadBackByteCount{0};
thread_local int diagnosticsScopes = 0;  // VulkanDevice::Diagnostics alive on this thread

bool validationWanted() {
#ifndef NDEBUG
    return true;
#else
    const char* v = std::getenv("HYBRIDLAB_VULKAN_VALIDATION");
    return v && std::strcmp(v, "0") != 0 && *v;
#endif
}

bool layerInstalled(const char* name) {
    std::uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

VKAPI_ATTR VkBool32 VKAPI_CALL debugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                            const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
    if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) std::fprintf(stderr, "vulkan validation: %s\n", data->pMessage);
    return VK_FALSE;
}

std::string versionText(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

// What the raster core needs of a device, or why it does not qualify.
std::optional<std::string> unsuitable(VkPhysicalDevice pd, std::uint32_t& queueFamily) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    if (p.apiVersion < VK_API_VERSION_1_3) return "supports Vulkan " + versionText(p.apiVersion) + ", not 1.3";
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13};
    vkGetPhysicalDeviceFeatures2(pd, &f);
    if (!f13.dynamicRendering) return std::string("lacks dynamicRendering");
    if (!f.features.samplerAnisotropy) return std::string("lacks samplerAnisotropy");
    if (!f.features.occlusionQueryPrecise) return std::string("lacks occlusionQueryPrecise");
    if (p.limits.maxColorAttachments < 8) return "has " + std::to_string(p.limits.maxColorAttachments) + " colour attachments, the G-buffer needs 8";
    if (!p.limits.timestampComputeAndGraphics) return std::string("has no timestamps on graphics queues");
    std::uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
    for (std::uint32_t i = 0; i < n; ++i) {
        if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && families[i].timestampValidBits > 0) {
            queueFamily = i;
            return std::nullopt;
        }
    }
    return std::string("has no graphics queue with timestamps");
}

// Discrete GPU, then integrated, then virtual, then a CPU device (lavapipe), then anything else.
int typePreference(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
        default: return 0;
    }
}

}  // namespace

// The extensions ray tracing needs (buffer device addresses and descriptor indexing are Vulkan 1.2 core).
const std::vector<const char*> kRayTracingExtensions = {
    VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
    VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
    VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME,
};

std::shared_ptr<VulkanDevice> VulkanDevice::shared(DeviceFeatures features) {
    static std::mutex mutex;
    // Released by releaseBeforeTheDriverAtExit, not by a static destructor: while the driver is
    // whole, its threads joined before LeakSanitizer's exit check.
    static auto& devices = *new std::map<DeviceFeatures, std::shared_ptr<VulkanDevice>>;
    static std::map<DeviceFeatures, std::string> failures;
    std::lock_guard lock(mutex);
    if (auto it = devices.find(features); it != devices.end()) return it->second;
    if (auto it = failures.find(features); it != failures.end()) throw VulkanUnavailable(it->second);
    try {
        std::shared_ptr<VulkanDevice> d(new VulkanDevice(features));
        d->create();
        devices[features] = d;
        releaseBeforeTheDriverAtExit([] {
            std::lock_guard exitLock(mutex);
            devices.clear();
        });
        return d;
    } catch (const VulkanUnavailable& e) {
        failures[features] = e.what();
        throw;
    }
}

std::vector<std::string> VulkanDevice::missingExtensions(VkPhysicalDevice pd, DeviceFeatures features) {
    std::vector<std::string> missing;
    if (!features.rayTracing) return missing;
    std::uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> available(n);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, available.data());
    const char* hidden = std::getenv("HYBRIDLAB_VULKAN_HIDE_EXTENSIONS");
    const std::string hide = hidden ? std::string(",") + hidden + "," : std::string();
    for (const char* wanted : kRayTracingExtensions) {
        bool found = false;
        for (const auto& e : available) found |= std::strcmp(e.extensionName, wanted) == 0;
        if (hide.find(std::string(",") + wanted + ",") != std::string::npos) found = false;
        if (!found) missing.emplace_back(wanted);
    }
    return missing;
}

VkDeviceSize VulkanDevice::deviceLocalBytes() const {
    // A test can play a device with less memory than this one has.
    if (const char* pretend = std::getenv("HYBRIDLAB_VULKAN_DEVICE_MEMORY_BYTES"); pretend && *pretend) {
        return static_cast<VkDeviceSize>(std::strtoull(pretend, nullptr, 10));
    }
    VkDeviceSize largest = 0;
    for (std::uint32_t i = 0; i < memory_.memoryHeapCount; ++i) {
        if (memory_.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) largest = std::max(largest, memory_.memoryHeaps[i].size);
    }
    return largest;
}

void VulkanDevice::create() {
    createInstance();
    choosePhysicalDevice();
    createLogicalDevice(rayTracingExtensionsToEnable());
    if (features_.rayTracing) loadRayTracingFunctions();
    createCommandPoolAndFence();
}

// The instance, with the validation layer and its messenger when wanted and installed.
void VulkanDevice::createInstance() {
    const bool validation = validationWanted() && layerInstalled(kValidationLayer);
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "hybridlab";
    app.apiVersion = VK_API_VERSION_1_3;
    std::vector<const char*> layers, extensions;
    if (validation) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    ici.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    ici.ppEnabledLayerNames = layers.data();
    ici.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    ici.ppEnabledExtensionNames = extensions.data();
    if (VkResult r = vkCreateInstance(&ici, nullptr, &instance_); r != VK_SUCCESS) {
        throw VulkanUnavailable(std::string("no Vulkan: cannot create a Vulkan instance (") + vkResultName(r) +
                                "); install the Vulkan loader and Mesa's lavapipe driver (./setup.sh installs libvulkan1 and "
                                "mesa-vulkan-drivers)");
    }
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
        mci.pfnUserCallback = debugMessage;
        if (create) create(instance_, &mci, nullptr, &messenger_);
    }
}

void VulkanDevice::choosePhysicalDevice() {
    std::uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance_, &count, devices.data());
    const char* wanted = std::getenv("HYBRIDLAB_VULKAN_DEVICE");
    // The most capable kind of device that qualifies (a GPU when there is one: lavapipe would time
    // the CPU), the first of a kind as the loader lists them; HYBRIDLAB_VULKAN_DEVICE narrows the
    // choice to the devices whose name holds it.
    std::string rejected;
    int bestScore = -1;
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        std::uint32_t family = 0;
        if (auto why = unsuitable(pd, family)) {
            rejected += std::string(rejected.empty() ? "" : "; ") + p.deviceName + " " + *why;
            continue;
        }
        VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
        vkGetPhysicalDeviceProperties2(pd, &p2);
        const bool isLavapipe = driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE;
        if (wanted && *wanted && !std::strstr(p.deviceName, wanted)) continue;
        const int score = typePreference(p.deviceType);
        if (score > bestScore) {
            bestScore = score;
            physical_ = pd;
            queueFamily_ = family;
            lavapipe_ = isLavapipe;
            driver_ = driver;
            driver_.pNext = nullptr;
        }
    }
    if (physical_ == VK_NULL_HANDLE) {
        std::string message = "no usable Vulkan device: ";
        if (count == 0) message += "the Vulkan loader found none (install mesa-vulkan-drivers for lavapipe; ./setup.sh does)";
        else if (wanted && *wanted && rejected.empty()) message += std::string("none matches HYBRIDLAB_VULKAN_DEVICE=") + wanted;
        else message += rejected;
        throw VulkanUnavailable(message);
    }
    vkGetPhysicalDeviceProperties(physical_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
}

// The device extensions ray tracing needs, when it was asked for; refuses a device without them.
std::vector<const char*> VulkanDevice::rayTracingExtensionsToEnable() {
    if (features_.rayTracing) {
        if (auto missing = missingExtensions(physical_, features_); !missing.empty()) {
            std::string list;
            for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
            throw VulkanUnavailable("Vulkan device " + name() + " (driver " + versionText(properties_.driverVersion) +
                                    ") lacks " + list + ", which ray tracing on the device needs (Mesa 25's lavapipe has it: ./setup.sh installs it)");
        }
        rayTracingProperties_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR;
        VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &rayTracingProperties_};
        vkGetPhysicalDeviceProperties2(physical_, &p2);
        // Rays are traced from the ray-generation shader only (its explicit stack, whitted.rgen):
        // a recursion depth of 1 is all the pipeline needs, which every ray-tracing device has.
        if (rayTracingProperties_.maxRayRecursionDepth < 1) {
            throw VulkanUnavailable("Vulkan device " + name() + " reports maxRayRecursionDepth 0; ray tracing needs 1");
        }
        return kRayTracingExtensions;
    }
    return {};
}

void VulkanDevice::createLogicalDevice(const std::vector<const char*>& extensions) {
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = queueFamily_;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.dynamicRendering = VK_TRUE;
    // glslc's SPIR-V 1.6 states compute shaders' group sizes with LocalSizeId, which needs
    // maintenance4 (core in 1.3, so every 1.3 device has it).
    f13.maintenance4 = VK_TRUE;
    VkPhysicalDeviceRayTracingPipelineFeaturesKHR rtf{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
    rtf.rayTracingPipeline = VK_TRUE;
    // Indirect launches (a compacted launch's size, written by its classification pass) where the
    // device has them (Mesa 25's lavapipe does); without, compacted launches fall back to full ones.
    if (features_.rayTracing) {
        VkPhysicalDeviceRayTracingPipelineFeaturesKHR has{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
        VkPhysicalDeviceFeatures2 query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &has};
        vkGetPhysicalDeviceFeatures2(physical_, &query);
        traceRaysIndirect_ = has.rayTracingPipelineTraceRaysIndirect == VK_TRUE;
        rtf.rayTracingPipelineTraceRaysIndirect = has.rayTracingPipelineTraceRaysIndirect;
    }
    VkPhysicalDeviceAccelerationStructureFeaturesKHR asf{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, &rtf};
    asf.accelerationStructure = VK_TRUE;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &asf};
    f12.bufferDeviceAddress = VK_TRUE;
    f12.descriptorIndexing = VK_TRUE;
    f12.runtimeDescriptorArray = VK_TRUE;
    f12.shaderSampledImageArrayNonUniformIndexing = VK_TRUE;
    if (features_.rayTracing) f13.pNext = &f12;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13};
    features.features.samplerAnisotropy = VK_TRUE;
    features.features.occlusionQueryPrecise = VK_TRUE;
    VkPhysicalDeviceFeatures supported;
    vkGetPhysicalDeviceFeatures(physical_, &supported);
    pipelineStatistics_ = supported.pipelineStatisticsQuery == VK_TRUE;  // the work counts; optional
    features.features.pipelineStatisticsQuery = supported.pipelineStatisticsQuery;
    features.features.shaderSampledImageArrayDynamicIndexing = features_.rayTracing ? VK_TRUE : VK_FALSE;
    // HYBRIDLAB_VULKAN_ROBUST=1: out-of-bounds buffer and image accesses read zeros instead of
    // faulting (a diagnosis of a device lost; off by default, as it costs time).
    if (const char* robust = std::getenv("HYBRIDLAB_VULKAN_ROBUST"); robust && std::string(robust) == "1") {
        features.features.robustBufferAccess = supported.robustBufferAccess;
        f13.robustImageAccess = VK_TRUE;
    }
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    dci.ppEnabledExtensionNames = extensions.data();
    if (VkResult r = vkCreateDevice(physical_, &dci, nullptr, &device_); r != VK_SUCCESS) {
        throw VulkanUnavailable(std::string("cannot create a Vulkan device on ") + properties_.deviceName + ": " + vkResultName(r));
    }
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
}

void VulkanDevice::loadRayTracingFunctions() {
    auto load = [&](auto& fn, const char* name) {
        fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(vkGetDeviceProcAddr(device_, name));
        if (!fn) throw VulkanUnavailable("Vulkan device " + this->name() + " has no entry point " + name);
    };
    load(rayTracing_.createAccelerationStructure, "vkCreateAccelerationStructureKHR");
    load(rayTracing_.destroyAccelerationStructure, "vkDestroyAccelerationStructureKHR");
    load(rayTracing_.getAccelerationStructureBuildSizes, "vkGetAccelerationStructureBuildSizesKHR");
    load(rayTracing_.getAccelerationStructureDeviceAddress, "vkGetAccelerationStructureDeviceAddressKHR");
    load(rayTracing_.cmdBuildAccelerationStructures, "vkCmdBuildAccelerationStructuresKHR");
    load(rayTracing_.createRayTracingPipelines, "vkCreateRayTracingPipelinesKHR");
    load(rayTracing_.getRayTracingShaderGroupHandles, "vkGetRayTracingShaderGroupHandlesKHR");
    load(rayTracing_.cmdTraceRays, "vkCmdTraceRaysKHR");
    if (traceRaysIndirect_) load(rayTracing_.cmdTraceRaysIndirect, "vkCmdTraceRaysIndirectKHR");
}

void VulkanDevice::createCommandPoolAndFence() {
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = queueFamily_;
    VkCommandPool pool;
    checkVk(vkCreateCommandPool(device_, &pci, nullptr, &pool), "creating a command pool");
    pool_ = UniqueCommandPool(device_, pool);
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence;
    checkVk(vkCreateFence(device_, &fci, nullptr, &fence), "creating a fence");
    fence_ = UniqueFence(device_, fence);
}

VulkanDevice::~VulkanDevice() {
    if (device_) vkDeviceWaitIdle(device_);
    fence_.reset();
    pool_.reset();
    if (device_) vkDestroyDevice(device_, nullptr);
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

UniqueDeviceMemory VulkanDevice::allocate(const VkMemoryRequirements& req, MemoryUse use, const char* what, bool deviceAddress,
                                          VkMemoryPropertyFlags* properties) const {
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, deviceAddress ? &flags : nullptr};
    ai.allocationSize = req.size;
    const std::vector<std::uint32_t> types = memoryTypeCandidates(memory_, req.memoryTypeBits, use);
    if (types.empty()) {
        throw VulkanError("Vulkan: " + name() + " has no memory type for " + what + " memory (" +
                          (use == MemoryUse::DeviceLocal ? "device-local" : "host-visible") + ")");
    }
    VkResult result = VK_ERROR_OUT_OF_DEVICE_MEMORY;
    VkDeviceMemory m = VK_NULL_HANDLE;
    for (std::uint32_t type : types) {
        ai.memoryTypeIndex = type;
        result = vkAllocateMemory(device_, &ai, nullptr, &m);
        // A full heap (a small BAR heap) leaves the next type to try.
        if (result != VK_ERROR_OUT_OF_DEVICE_MEMORY) break;
    }
    checkVk(result, (std::string("allocating ") + what + " memory").c_str());
    if (properties) *properties = memory_.memoryTypes[ai.memoryTypeIndex].propertyFlags;
    countAllocations(1);
    return UniqueDeviceMemory(device_, m);
}

void VulkanDevice::requireFormat(VkFormat format, VkFormatFeatureFlags features, const char* purpose) const {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(physical_, format, &p);
    if ((p.optimalTilingFeatures & features) != features) {
        throw VulkanUnavailable("Vulkan device " + name() + " does not support image format " + std::to_string(format) + " for " +
                                purpose);
    }
}

void VulkanDevice::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
    // The pool is externally synchronised, recording included: hold the lock throughout.
    std::lock_guard lock(submitMutex_);
    if (commandBuffers_.size() == recordingDepth_) {
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = pool_;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        VkCommandBuffer allocated;
        checkVk(vkAllocateCommandBuffers(device_, &ai, &allocated), "allocating a command buffer");
        countAllocations(1);
        commandBuffers_.push_back(allocated);
    }
    VkCommandBuffer cb = commandBuffers_[recordingDepth_];
    struct Depth {
        std::size_t& depth;
        explicit Depth(std::size_t& d) : depth(d) { ++depth; }
        ~Depth() { --depth; }
    } nested(recordingDepth_);
    checkVk(vkResetCommandBuffer(cb, 0), "resetting a command buffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    checkVk(vkBeginCommandBuffer(cb, &bi), "beginning a command buffer");
    record(cb);
    checkVk(vkEndCommandBuffer(cb), "recording commands");
    submitAndWait(cb);
}

void VulkanDevice::submitAndWait(VkCommandBuffer commands) const {
    std::lock_guard lock(submitMutex_);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &commands;
    checkVk(vkQueueSubmit(queue_, 1, &si, fence_), "submitting commands");
    ++(diagnosticsScopes > 0 ? diagnosticSubmissionCount : submissionCount);
    // A GPU that has not finished a submission in two minutes has hung (a shader that never ends,
    // a fault the driver did not report): an error, not a wait without end. A CPU device
    // (lavapipe) may take that long for one frame of rays, so it is waited for.
    const std::uint64_t timeoutNs = type() == VK_PHYSICAL_DEVICE_TYPE_CPU ? UINT64_MAX : 120'000'000'000ull;
    const VkResult waited = vkWaitForFences(device_, 1, fence_.ptr(), VK_TRUE, timeoutNs);
    if (waited == VK_TIMEOUT) throw VulkanError("Vulkan: " + name() + " did not finish a submission within 120 s (a hang)");
    checkVk(waited, "waiting for the GPU");
    checkVk(vkResetFences(device_, 1, fence_.ptr()), "resetting a fence");
}

DeviceWork VulkanDevice::workSoFar() {
    return {submissionCount.load(), readBackByteCount.load(), allocationCount.load(), diagnosticSubmissionCount.load(),
            diagnosticReadBackByteCount.load()};
}

void VulkanDevice::countReadBack(std::uint64_t bytes) { (diagnosticsScopes > 0 ? diagnosticReadBackByteCount : readBackByteCount) += bytes; }

VulkanDevice::Diagnostics::Diagnostics() { ++diagnosticsScopes; }

VulkanDevice::Diagnostics::~Diagnostics() { --diagnosticsScopes; }

void VulkanDevice::countAllocations(std::uint64_t objects) { allocationCount += objects; }

}  // namespace hybridlab
