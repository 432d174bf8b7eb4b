#pragma once
// A rasterizer frame as stages of the vocabulary (techniques/stage_names.h): its GPU passes by
// their timestamps, the read-back with the host's unpacking, and what the timestamps do not cover
// (recording, submission, waking up) as `overhead`, so that the stages add up to the wall clock.
#include <string>
#include <vector>

#include "common/raster/rasterizer.h"
#include "techniques/stage_clock.h"

namespace hybridlab {

// Ends `clock`'s current stage, which rendered `frame` (and did nothing else worth a stage of its
// own). The rasterizer's passes are named as the stages they are (RasterFrame::gpuStages);
// `recordedWithIt` are the stages of the rest of the device work in the frame's submission
// (RasterRequest::first and last: a G-buffer cast, a ray launch), by their GPU times.
inline void lapRasterFrame(StageClock& clock, const RasterFrame& frame, const std::vector<StageTime>& recordedWithIt = {}) {
    std::vector<StageTime> passes;
    for (const RasterStageTime& s : frame.gpuStages)
        passes.push_back({s.name, s.milliseconds + (s.name == "readback" ? frame.unpackMilliseconds : 0.0)});
    passes.insert(passes.end(), recordedWithIt.begin(), recordedWithIt.end());
    clock.lap(passes, "overhead");
}

}  // namespace hybridlab
