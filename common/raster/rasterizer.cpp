#include "common/raster/rasterizer.h"

#include "common/core/wall_clock.h"
#include "common/raster/deferred_lighting.h"
#include "common/raster/frame_pass.h"
#include "common/raster/gbuffer_pass.h"
#include "common/raster/gpu_scene.h"
#include "common/raster/gpu_timer.h"
#include "common/raster/shadow_maps.h"
#include "common/raster/vulkan_error.h"

namespace hybridlab {

namespace {

// A G-buffer not drawn by the G-buffer pass (uploaded, or written on the device at the size of the
// targets, before they are resized) has no occlusion queries, and the device's no depth target.
void checkGBufferSource(const RasterRequest& request, const GBufferPass& gbuffer) {
    if ((request.hostGBuffer || request.deviceGBuffer) && request.occlusionQueries)
        throw VulkanError("Rasterizer: no occlusion queries without the G-buffer pass");
    if (!request.deviceGBuffer) return;
    if (request.readback & kGBufferDepth) throw VulkanError("Rasterizer: a G-buffer written on the device has no depth target to read back");
    if (gbuffer.width() != static_cast<std::uint32_t>(request.width) || gbuffer.height() != static_cast<std::uint32_t>(request.height)) {
        throw VulkanError("Rasterizer: the G-buffer written on the device is " + std::to_string(gbuffer.width()) + " x " +
                          std::to_string(gbuffer.height()) + ", the frame " + std::to_string(request.width) + " x " +
                          std::to_string(request.height));
    }
}

// The timer's stages as the frame records them: times, and work counts where the device has them.
std::vector<RasterStageTime> rasterStageTimes(const std::vector<GpuStageTime>& stages) {
    std::vector<RasterStageTime> out;
    for (const GpuStageTime& s : stages) {
        out.push_back({s.name, s.milliseconds});
        if (!s.statistics) continue;
        RasterStageTime& t = out.back();
        t.counted = true;
        t.inputPrimitives = s.statistics->inputPrimitives;
        t.clippingPrimitives = s.statistics->clippingPrimitives;
        t.fragmentInvocations = s.statistics->fragmentInvocations;
        t.computeInvocations = s.statistics->computeInvocations;
    }
    return out;
}

}  // namespace

double RasterFrame::gpuMilliseconds(const std::string& stage) const {
    for (const auto& s : gpuStages)
        if (s.name == stage) return s.milliseconds;
    return 0.0;
}

struct Rasterizer::Impl {
    static constexpr std::uint32_t kMaxGpuStages = 16;  // the fixed passes and a technique's own
    std::shared_ptr<VulkanDevice> device;
    GpuScene scene;
    GBufferPass gbuffer;
    ShadowMaps shadows;
    DeferredLighting lighting;
    GpuTimer timer;
    UniqueCommandPool pool;
    VkCommandBuffer commands = VK_NULL_HANDLE;  // freed with the pool
    UniqueQueryPool occlusion;
    double uploadMs = 0.0;
    RasterRequest last;  // camera and size of the last frame (targets())

    Impl(std::shared_ptr<VulkanDevice> d, const Scene& s, DeformedMeshCache* deformedMeshes)
        : device(std::move(d)), scene(device, s, deformedMeshes), gbuffer(scene), shadows(scene), lighting(scene, gbuffer, shadows), timer(*device, kMaxGpuStages) {
        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        VkCommandPool p;
        checkVk(vkCreateCommandPool(device->device(), &pci, nullptr, &p), "creating the rasterizer's command pool");
        pool = UniqueCommandPool(device->device(), p);
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = p;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        checkVk(vkAllocateCommandBuffers(device->device(), &ai, &commands), "allocating the rasterizer's command buffer");
        VulkanDevice::countAllocations(1);
        VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qci.queryType = VK_QUERY_TYPE_OCCLUSION;
        qci.queryCount = static_cast<std::uint32_t>(std::max<std::size_t>(1, s.objects.size()));
        VkQueryPool q;
        checkVk(vkCreateQueryPool(device->device(), &qci, nullptr, &q), "creating the occlusion query pool");
        occlusion = UniqueQueryPool(device->device(), q);
    }
};

Rasterizer::Rasterizer(const Scene& scene, DeformedMeshCache* deformedMeshes) : Rasterizer(scene, deformedMeshes, DeviceFeatures{}) {}

Rasterizer::Rasterizer(const Scene& scene, DeformedMeshCache* deformedMeshes, const DeviceFeatures& features) {
    const auto start = WallClock::now();
    impl_ = std::make_unique<Impl>(VulkanDevice::shared(features), scene, deformedMeshes);
    impl_->uploadMs = millisecondsSince(start);
}

FrameTargets Rasterizer::targets() const {
    const Impl& r = *impl_;
    FrameTargets t;
    t.width = r.gbuffer.width();
    t.height = r.gbuffer.height();
    t.camera = r.last.camera;
    if (t.width == 0) return t;
    const float aspect = static_cast<float>(t.width) / static_cast<float>(t.height);
    t.view = t.camera.view();
    t.projection = t.camera.projectionMatrix(aspect);
    for (int i = 0; i < GBufferPass::kColorTargets; ++i) t.gbuffer[i] = r.gbuffer.targetView(i);
    t.lighting = r.last.lighting ? r.lighting.output() : VK_NULL_HANDLE;
    return t;
}

GBufferStorage Rasterizer::gbufferStorage(int width, int height) {
    if (width <= 0 || height <= 0) throw VulkanError("Rasterizer: the frame size must be positive");
    impl_->gbuffer.resize(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
    return impl_->gbuffer.storage();
}

Rasterizer::~Rasterizer() = default;

std::string Rasterizer::deviceName() const { return impl_->device->name(); }
double Rasterizer::uploadMilliseconds() const { return impl_->uploadMs; }

RasterFrame Rasterizer::render(const RasterRequest& request) {
    RasterFrame frame;
    render(request, frame);
    return frame;
}

void Rasterizer::render(const RasterRequest& request, RasterFrame& frame) {
    if (request.width <= 0 || request.height <= 0) throw VulkanError("Rasterizer: the frame size must be positive");
    Impl& r = *impl_;
    auto start = WallClock::now();
    const bool moved = r.scene.setTime(request.time);
    checkGBufferSource(request, r.gbuffer);
    r.gbuffer.resize(static_cast<std::uint32_t>(request.width), static_cast<std::uint32_t>(request.height));
    const float aspect = static_cast<float>(request.width) / static_cast<float>(request.height);
    const glm::mat4 viewProj = request.camera.projectionMatrix(aspect) * request.camera.view();

    VkCommandBuffer cb = r.commands;
    checkVk(vkResetCommandBuffer(cb, 0), "resetting the frame's command buffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    checkVk(vkBeginCommandBuffer(cb, &bi), "beginning the frame's command buffer");
    // Lavapipe (Mesa 25.0.7) crashes on a pipeline-statistics query after vkCmdTraceRaysKHR in one
    // command buffer: there, a frame that starts with a ray launch (a G-buffer cast) is timed
    // without its passes' work counts.
    r.timer.reset(cb, !(request.first && r.device->isLavapipe()));
    if (request.first) request.first(cb);
    frame.shadowMapsDrawn = false;
    if (request.lighting && request.lightingOptions.shadows) {
        r.timer.begin(cb, "shadow_maps");
        frame.shadowMapsDrawn = r.shadows.record(cb, request.shadowSettings, moved || request.redrawShadowMaps);
        r.timer.end(cb);
    }
    if (request.hostGBuffer) {
        r.timer.begin(cb, "gbuffer.upload");
        r.gbuffer.recordUpload(cb, *request.hostGBuffer);
        r.timer.end(cb);
        frame.draws = 0;
    } else if (request.deviceGBuffer) {
        r.gbuffer.recordWrittenOnDevice(cb);
        frame.draws = 0;
    } else {
        r.timer.begin(cb, "gbuffer");
        frame.draws = r.gbuffer.record(cb, viewProj);
        r.timer.end(cb);
        if (request.occlusionQueries) {
            r.timer.begin(cb, "heuristic.visible_pixels");
            r.gbuffer.recordVisiblePixelQueries(cb, viewProj, r.occlusion);
            r.timer.end(cb);
        }
        r.gbuffer.recordFinish(cb);
    }
    const GBufferTargets readback = request.hostGBuffer ? 0 : request.readback;
    if (request.lighting) {
        r.timer.begin(cb, "lighting");
        r.lighting.record(cb, request.camera, request.lightingOptions, request.shadowSettings);
        r.timer.end(cb);
    }
    r.last.camera = request.camera;
    r.last.lighting = request.lighting;
    if (!request.passes.empty()) {
        const FrameTargets targets = this->targets();
        for (RasterFramePass* pass : request.passes) {
            r.timer.begin(cb, pass->name());
            pass->record(cb, targets);
            r.timer.end(cb);
        }
    }
    r.timer.begin(cb, "readback");
    if (readback) r.gbuffer.recordReadback(cb, readback);
    if (request.lighting && request.lightingReadback) r.lighting.recordReadback(cb);
    r.timer.end(cb);
    if (request.last) request.last(cb);
    checkVk(vkEndCommandBuffer(cb), "recording the frame");
    frame.recordMilliseconds = millisecondsSince(start);

    start = WallClock::now();
    r.device->submitAndWait(cb);
    frame.submitMilliseconds = millisecondsSince(start);

    start = WallClock::now();
    if (request.hostGBuffer) frame.gbuffer = GBuffer{};  // the technique holds it
    else r.gbuffer.unpack(readback, frame.gbuffer);
    if (request.lighting && request.lightingReadback) r.lighting.unpack(frame.lighting);
    else frame.lighting = Image();
    frame.visiblePixelsByQuery.clear();
    if (request.occlusionQueries) {
        const std::size_t n = r.scene.scene().objects.size();
        frame.visiblePixelsByQuery.resize(n);
        if (n > 0) {
            checkVk(vkGetQueryPoolResults(r.device->device(), r.occlusion, 0, static_cast<std::uint32_t>(n), n * sizeof(std::uint64_t),
                                          frame.visiblePixelsByQuery.data(), sizeof(std::uint64_t),
                                          VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
                    "reading the occlusion queries");
            VulkanDevice::countReadBack(n * sizeof(std::uint64_t));
        }
    }
    for (RasterFramePass* pass : request.passes) pass->finish();
    frame.gpuStages = rasterStageTimes(r.timer.read());
    frame.unpackMilliseconds = millisecondsSince(start);
}

}  // namespace hybridlab
