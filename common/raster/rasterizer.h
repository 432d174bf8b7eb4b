#pragma once
// The shared rasterizer of a scene (DESIGN.md "A frame, as data"): the G-buffer, deferred lighting
// and shadow maps on a headless Vulkan device, with read-back of what the technique asks for. The
// scene is uploaded once (geometry, materials, mip-mapped textures); each frame is one command
// buffer, timed per pass with GPU timestamps. Free of Vulkan headers: techniques include it.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/image/image.h"
#include "common/raster/gbuffer.h"
#include "common/raster/raster_options.h"
#include "common/scene/camera.h"
#include "common/scene/scene.h"

// Vulkan's command buffer handle, as vulkan_core.h defines it (VK_DEFINE_HANDLE), without its header.
typedef struct VkCommandBuffer_T* VkCommandBuffer;

namespace hybridlab {

class RasterFramePass;     // common/raster/frame_pass.h
struct FrameTargets;       // common/raster/frame_pass.h
struct GBufferStorage;     // common/raster/gbuffer_pass.h
struct DeviceFeatures;     // common/raster/vulkan_device.h
class DeformedMeshCache;   // common/scene/deformed_mesh_cache.h

struct RasterRequest {
    Camera camera;
    double time = 0.0;
    int width = 0;
    int height = 0;
    GBufferTargets readback = 0;        // G-buffer targets to read back (only these are copied)
    bool lighting = true;               // run the lighting pass and read its image back
    bool lightingReadback = true;       // false: the lit image stays on the device (targets()), RasterFrame::lighting is empty
    LightingOptions lightingOptions;
    ShadowSettings shadowSettings;      // when lightingOptions.shadows
    bool redrawShadowMaps = false;      // else shadow maps are redrawn only when something moved or the settings changed
    bool occlusionQueries = false;      // visible pixels per object by precise occlusion queries in a depth-equal pass
    // A G-buffer made on the host (primary rays: techniques/shared/ray_cast_gbuffer.h), holding every
    // colour target at the request's size: the G-buffer pass is skipped and these are uploaded in its
    // place (stage "gbuffer.upload"); nothing of the G-buffer is read back and occlusion queries are
    // not available. Null: the G-buffer pass.
    const GBuffer* hostGBuffer = nullptr;
    // The colour targets were written on the device since gbufferStorage() at the request's size
    // (primary rays: common/device_rays/device_gbuffer_caster.h): the G-buffer pass is skipped and
    // the frame reads them where they lie. The depth target is not written (no later pass reads it:
    // SSR builds its depth pyramid from the position target), so it cannot be read back, and
    // occlusion queries are not available.
    bool deviceGBuffer = false;
    // A technique's own passes (SSR, ...), recorded in order after the lighting pass and before the
    // read-back, each timed under its name; finish() is called on each after the frame completed.
    std::vector<RasterFramePass*> passes;
    // The rest of the frame's device work, recorded into the frame's command buffer so that the
    // frame is one submission and one wait: `first` before the rasterizer's passes (the G-buffer
    // cast on the device), `last` after its read-back (a ray launch over targets(), the copies of
    // what the host reads after the frame). Each times its own work; results are read after render().
    std::function<void(VkCommandBuffer)> first, last;
};

struct RasterStageTime {
    std::string name;
    double milliseconds = 0.0;
    // The pass's work by pipeline-statistics query (gpu_timer.h), where the device counts it.
    bool counted = false;
    std::uint64_t inputPrimitives = 0, clippingPrimitives = 0, fragmentInvocations = 0, computeInvocations = 0;
};

struct RasterFrame {
    GBuffer gbuffer;                      // the requested targets
    Image lighting;                       // when RasterRequest::lighting: linear RGBA (the P-buffer)
    std::vector<std::uint64_t> visiblePixelsByQuery;  // per object, when RasterRequest::occlusionQueries
    // GPU timestamps per pass, in order, each named as the stage it is (techniques/stage_names.h):
    // shadow_maps (when shadows are on; near 0 when the maps were kept), gbuffer (depth pre-pass
    // included; gbuffer.upload instead with a host G-buffer, none with one written on the device),
    // heuristic.visible_pixels (when asked), lighting (when asked), the request's own passes by
    // name, readback (the copies).
    std::vector<RasterStageTime> gpuStages;
    // Wall clock: recording the commands, submission until completion, unpacking the read-back.
    double recordMilliseconds = 0.0, submitMilliseconds = 0.0, unpackMilliseconds = 0.0;
    bool shadowMapsDrawn = false;
    std::size_t draws = 0;                // G-buffer draws after frustum culling

    double gpuMilliseconds(const std::string& stage) const;  // 0 when the stage did not run
    double wallMilliseconds() const { return recordMilliseconds + submitMilliseconds + unpackMilliseconds; }
};

class Rasterizer {
public:
    // Uploads the scene. Throws VulkanUnavailable when there is no usable Vulkan device (the
    // message says why), VulkanError for other failures.
    // `deformedMeshes`: shared with the ray scene (deformed_mesh_cache.h), or null for a cache of its own.
    // `features`: the device to rasterize on (VulkanDevice::shared); with ray tracing, the device
    // whose ray-tracing pipelines read the targets where they lie (targets()).
    explicit Rasterizer(const Scene& scene, DeformedMeshCache* deformedMeshes = nullptr);
    Rasterizer(const Scene& scene, DeformedMeshCache* deformedMeshes, const DeviceFeatures& features);
    ~Rasterizer();
    Rasterizer(const Rasterizer&) = delete;
    Rasterizer& operator=(const Rasterizer&) = delete;

    // Renders one frame into `frame`, reusing its buffers.
    void render(const RasterRequest& request, RasterFrame& frame);
    RasterFrame render(const RasterRequest& request);

    // The last frame's targets on the device (every view in VK_IMAGE_LAYOUT_GENERAL after render()),
    // for passes that run after the frame: RasterRequest::last, or submissions of their own.
    FrameTargets targets() const;

    // The G-buffer's colour targets at width x height as storage images, for a G-buffer written on
    // the device before a frame with RasterRequest::deviceGBuffer. Ray-tracing devices only.
    GBufferStorage gbufferStorage(int width, int height);

    std::string deviceName() const;
    double uploadMilliseconds() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace hybridlab
