#pragma once
// A frame's rasterizer work as FrameResult counters, under the same names for every technique:
// per GPU pass with pipeline-statistics queries (gpu_timer.h), vk_<pass>_input_primitives,
// _clipping_primitives, _fragment_invocations and _compute_invocations. Work, unlike time, carries
// over between machines.
#include "common/raster/rasterizer.h"
#include "techniques/technique.h"

namespace hybridlab {

inline void recordRasterWork(const RasterFrame& frame, FrameResult& result) {
    for (const RasterStageTime& s : frame.gpuStages) {
        if (!s.counted) continue;
        const std::string prefix = "vk_" + s.name + "_";
        result.counters[prefix + "input_primitives"] = static_cast<double>(s.inputPrimitives);
        result.counters[prefix + "clipping_primitives"] = static_cast<double>(s.clippingPrimitives);
        result.counters[prefix + "fragment_invocations"] = static_cast<double>(s.fragmentInvocations);
        result.counters[prefix + "compute_invocations"] = static_cast<double>(s.computeInvocations);
    }
}

}  // namespace hybridlab
