#pragma once
// `heuristic_rt`: heuristic-selected hybrid ray tracing (Walewski 2019 §3, with Sabino 2012's
// selection graph). Four timed stages per frame, as Walewski's Table 5 (its RAST, HEUR, RAYT, BLEND
// under the names every technique uses):
//   raster    the shared G-buffer and deferred lighting (the P-buffer);
//   heuristic per visible object A, P, D, V, Q, C, R (eqs. 1-3), the selection graph and the
//         selection loop of Listing 6 against the budget T; its output is the heuristic mask;
//   trace Embree, for masked pixels only, from the G-buffer (no primary rays): shadow rays,
//         reflection and refraction recursive to max_depth with the importance cut-off, the sky on
//         a miss (Listings 8a-8d);
//   blend Listing 10: unmasked pixels keep the P-buffer; masked ones compose the traced terms with
//         the shading model's composition (default, so that an unlimited budget reproduces the reference) or
//         eqs. (5)-(6) (`blend = "walewski2019"`).
// `heuristic = false` selects every visible object (the paper's "no heuristic" run). Beyond the
// paper (§5-6): `target_ms` sets T each frame from a learned cost-to-time rate, and `per_effect`
// selects shadows, reflections and refractions separately per object.
// With `rays = "vulkan"` the frame stays on the ray-tracing device: the rasterizer runs there (with
// `gbuffer = "rays"` the primary rays too, into its targets), the visible pixels are counted there
// (object_pixel_count_pass.h) and read back as one count an object, the selection goes down as one
// word an object, and the trace and blend run in one ray-generation shader over the G-buffer where
// it lies (shaders/device_heuristic_rt.rgen); the host reads back the final image (and the debug
// images, outside the timed stages).
// With `gbuffer = "rays"` and `lighting = "cpu"` the frame stays on Embree instead: the P-buffer
// of the pixels the mask leaves untraced is lit on the CPU (stage lighting.cpu) by the shading
// model the rasterizer's lighting pass computes, with shadow rays (`raster_shadows = "rays"`) or
// none in place of the maps; no rasterizer is created (README.md says why).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "common/raster/rasterizer.h"
#include "common/raytrace/whitted_tracer.h"
#include "common/device_rays/device_gbuffer_tracer.h"
#include "common/shading/whitted_tree_types.h"
#include "techniques/heuristic_rt/frame_time_budget.h"
#include "techniques/heuristic_rt/object_pixel_count_pass.h"
#include "techniques/shared/device_launch_parameters.h"
#include "techniques/shared/gbuffer_source.h"
#include "techniques/shared/ray_backend_parameters.h"
#include "techniques/shared/recursion_parameters.h"
#include "techniques/shared/traced_shading_parameters.h"
#include "techniques/technique.h"

namespace hybridlab {

struct HeuristicRtParameters {
    double budget{};                       // T; 0: unlimited
    double targetMilliseconds{};           // 0: `budget`
    double previousSelectionImportance{};  // I
    bool heuristic{};
    bool perEffect{};
    bool visiblePixelsByQueries{};
    // raster_shadows: the shadows of pixels not ray traced.
    enum class UnselectedShadows { Map, Off, Rays } unselectedShadows{};
    bool cpuLighting{};  // lighting = "cpu"
    bool debugImages{};
    GBufferSourceParameters gbuffer;
    RayBackendParameters rays;
    DeviceLaunchParameters launch;
    RecursionParameters recursion;
    TracedShadingParameters shading;
};

class HeuristicRtTechnique : public Technique {
public:
    static TechniqueInfo info();

    explicit HeuristicRtTechnique(const HeuristicRtParameters& params);
    void prepare(SceneContext& context) override;
    FrameResult render(SceneContext& context, const FrameRequest& frame) override;

private:
    // The selection of this frame: per object, bits of the effects (1 << Effect) to trace.
    struct Selection {
        std::vector<std::uint8_t> effectsByObject;
        std::size_t objectsVisible = 0, objectsSelected = 0;
        double costVisible = 0.0, costSelected = 0.0, budget = 0.0;
    };
    Selection selectObjects(const Scene& scene, const FrameRequest& frame, const std::vector<std::uint64_t>& visiblePixels);
    RasterRequest rasterRequest(const FrameRequest& frame) const;
    FrameResult renderOnDevice(SceneContext& context, const FrameRequest& frame);
    // lighting = "cpu": the P-buffer's pixels that the mask leaves untraced, into `pbuffer`.
    RayStats lightUnmaskedPixels(const RayScene& rays, const GBuffer& g, const FrameRequest& frame, Image& pbuffer) const;
    // The counters both paths record after the trace (and the frame-time budget's observation).
    void recordFrame(const Selection& selection, const RayStats& stats, std::size_t masked, FrameResult& result);

    WhittedSettings tracer_;
    double budget_ = 0.0;                   // T; 0: unlimited
    double previousSelectionImportance_;    // I
    bool heuristic_ = true;
    bool perEffect_ = false;
    bool visiblePixelsByQueries_ = false;
    bool rasterShadows_ = true;             // raster_shadows = "map"
    bool unselectedShadowRays_ = false;     // raster_shadows = "rays"
    bool cpuLighting_ = false;              // lighting = "cpu"
    bool debugImages_ = true;
    bool onDevice_ = false;                 // rays = "vulkan"
    DeviceLaunchParameters launch_;         // with rays = "vulkan"
    std::optional<FrameTimeBudget> frameTimeBudget_;  // when target_ms > 0

    std::vector<Aabb> localBounds_;          // per object, object space (for P and D)
    RasterFrame raster_;
    GBufferSource gbuffer_;
    std::vector<shading_language::HitParts> parts_;  // per pixel, for masked pixels
    std::vector<std::uint8_t> pixelEffects_; // per pixel: the heuristic mask (effect bits)
    std::vector<bool> selectedLastFrame_;    // S, per object
    std::unique_ptr<DeviceGBufferTracer> deviceTracer_;  // rays = "vulkan"
    std::unique_ptr<ObjectPixelCountPass> pixelCounts_;  // rays = "vulkan", visible_pixels = "ids"
};

}  // namespace hybridlab
