#pragma once
// A rasterizer frame as stages of the vocabulary (techniques/stage_names.h): its GPU passes by
// their timestamps, the read-back with the host's unpacking, and what the timestamps do not cover
// (recording, submission, waking up) as `overhead`, so that the stages add up to the wall clock.
#include <string>
#include <vector>

#include "common/raster/rasterizer.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

// The stage a rasterizer pass is timed under. The rasterizer names its passes (and their work
// counters, vk_<pass>_*) by what they draw; the stage names say what the work is for.
inline std::string rasterPassStage(const std::string& pass) {
    if (pass == "gbuffer_upload") return "gbuffer.upload";
    if (pass == "visible_pixels") return "heuristic.visible_pixels";
    if (pass == "lens_draw") return "lens.draw";
    return pass;  // shadow_maps, gbuffer, lighting, ssr, readback
}

// Ends `clock`'s current stage, which rendered `frame` (and did nothing else worth a stage of its own).
inline void lapRasterFrame(StageClock& clock, const RasterFrame& frame) {
    std::vector<StageTime> passes;
    for (const RasterStageTime& s : frame.gpuStages)
        passes.push_back({rasterPassStage(s.name), s.milliseconds + (s.name == "readback" ? frame.unpackMilliseconds : 0.0)});
    clock.lap(passes, "overhead");
}

}  // namespace hybridlab
