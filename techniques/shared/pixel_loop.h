#pragma once
// The per-pixel ray-tracing loop every ray-traced stage shares: parallel over image tiles (TBB),
// one RayStats per thread, summed at the end; deterministic (each pixel is independent, and every
// task runs in the one floating-point mode of ray_task_context.h).
#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "common/raytrace/ray_stats.h"
#include "common/raytrace/ray_task_context.h"

namespace hybridlab {

// Calls perPixel(x, y, stats) for every pixel of a width x height image; returns the summed stats.
template <class PerPixel>
RayStats forEachPixelInParallel(int width, int height, PerPixel&& perPixel) {
    tbb::combinable<RayStats> statsPerThread;
    constexpr int kTile = 16;
    RayTaskContext context;
    tbb::parallel_for(tbb::blocked_range2d<int>(0, height, kTile, 0, width, kTile), [&](const tbb::blocked_range2d<int>& r) {
        RayStats& stats = statsPerThread.local();
        for (int y = r.rows().begin(); y < r.rows().end(); ++y)
            for (int x = r.cols().begin(); x < r.cols().end(); ++x) perPixel(x, y, stats);
    }, context);
    RayStats total;
    statsPerThread.combine_each([&](const RayStats& s) { total += s; });
    return total;
}

}  // namespace hybridlab
