#pragma once
// `layered_em`: hybrid rendering with layered inferred environment maps (Hakura & Snyder 2001).
// prepare() bakes (or loads from the cache, em_cache.h) the layered EMs of every lens system; each
// frame draws the G-buffer and deferred lighting of the scene, traces the two ray paths at the lens
// vertices from the current viewpoint with adaptive tessellation (§5), generates the per-vertex
// cube-map indices and draws the lenses with the EMs on the GPU (layered_em_pass.h) over the lit
// image. The paper's results table's stages are trace.lens_vertices (vertex ray tracing),
// lens.texture_coordinates, lens.tessellation, and the rest (rendering included).
#include <memory>
#include <vector>

#include "common/raster/rasterizer.h"
#include "techniques/layered_em/em_bake.h"
#include "techniques/layered_em/layered_em_pass.h"
#include "techniques/shared/raster_warm_up.h"
#include "techniques/shared/shadow_parameters.h"
#include "techniques/technique.h"

namespace hybridlab {

struct LayeredEmParameters {
    int layers{};
    bool singleLayer{};
    float tau{};  // per frame
    int emSize{};
    float viewpointStep{};  // degrees
    int viewpoints{};
    int bakeWidth{}, bakeHeight{};
    int supersampling{};
    float confidenceAngle{};  // degrees
    int neighbourViewpoints{};
    bool disocclusionPrevention{};
    DirectImageSource directImages{};
    bool originImages{};
    bool viewpointBlending{};
    bool emCache{};
    ShadowMapParameters shadowMaps;
};

class LayeredEmTechnique : public Technique {
public:
    static TechniqueInfo info();
    // The bake settings the parameters give.
    static EmBakeSettings bakeSettings(const LayeredEmParameters& params);

    explicit LayeredEmTechnique(const LayeredEmParameters& params);
    ~LayeredEmTechnique() override;

    void prepare(SceneContext& context) override;
    FrameResult render(SceneContext& context, const FrameRequest& frame) override;

private:
    struct System;
    RasterRequest rasterRequest(const FrameRequest& frame);

    EmBakeSettings bake_;                     // its tessellation is at the bake's lens-image resolution
    TessellationSettings frameTessellation_;  // per frame, at the frame's resolution
    bool blendViewpoints_ = true;
    bool useCache_ = true;
    ShadowSettings shadowSettings_;
    std::vector<std::unique_ptr<System>> systems_;
    std::vector<LayeredEm> ems_;
    std::unique_ptr<LayeredEmPass> pass_;
    RasterFrame raster_;
    RasterWarmUp warmUp_;
};

}  // namespace hybridlab
