#pragma once
// The floating-point mode of every parallel loop that traces rays: flush-to-zero and
// denormals-are-zero, as Embree asks of the threads that call rtcIntersect and rtcOccluded (Embree 3
// manual, "Performance Recommendations": MXCSR control and status register). Set, not inherited:
// TBB tasks otherwise run in the mode of the thread that started TBB's arena, which is FTZ/DAZ when
// Embree's first BVH build starts it and IEEE when another parallel loop (the rasterizer's) ran
// first. The same frame then traced a different number of shadow rays (a light term flushed to 0
// needs none) depending on what the process had rendered before.
#include <tbb/task_group.h>

namespace hybridlab {

// Pass to tbb::parallel_for: its tasks run in the ray-tracing mode on whichever thread, the calling
// one included; the calling thread's own mode is left as it was.
class RayTaskContext : public tbb::task_group_context {
public:
    RayTaskContext();
};

}  // namespace hybridlab
