#pragma once
// The per-pixel ray-tracing loop every ray-traced stage shares: parallel over image tiles (TBB),
// one RayStats per thread, summed at the end; deterministic (each pixel is independent, and every
// task runs in the one floating-point mode of ray_task_context.h).
#include <algorithm>

#include <tbb/blocked_range2d.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "common/raytrace/ray_stats.h"
#include "common/raytrace/ray_task_context.h"

namespace hybridlab {

// A block of up to kWidth x kHeight pixels, clipped to the image: the camera rays of one coherent
// packet (RayScene::intersectCoherent), pixel k at (x[k], y[k]), row by row.
struct PixelBlock {
    static constexpr int kWidth = 4, kHeight = 2;
    int count = 0;
    int x[kWidth * kHeight];
    int y[kWidth * kHeight];
};

// Calls perBlock(block, stats) for the blocks of kWidth x kHeight pixels on a fixed grid over a
// width x height image, in tiles of 4 x 8 blocks; returns the summed stats. The grid does not
// depend on how TBB splits the work, so each packet holds the same rays on every run.
template <class PerBlock>
RayStats forEachPixelBlockInParallel(int width, int height, PerBlock&& perBlock) {
    constexpr int kW = PixelBlock::kWidth, kH = PixelBlock::kHeight;
    tbb::combinable<RayStats> statsPerThread;
    RayTaskContext context;
    const int columns = (width + kW - 1) / kW, rows = (height + kH - 1) / kH;
    tbb::parallel_for(tbb::blocked_range2d<int>(0, rows, 16 / kH, 0, columns, 16 / kW), [&](const tbb::blocked_range2d<int>& r) {
        RayStats& stats = statsPerThread.local();
        PixelBlock block;
        for (int by = r.rows().begin(); by < r.rows().end(); ++by) {
            for (int bx = r.cols().begin(); bx < r.cols().end(); ++bx) {
                block.count = 0;
                for (int y = by * kH; y < std::min(by * kH + kH, height); ++y) {
                    for (int x = bx * kW; x < std::min(bx * kW + kW, width); ++x) {
                        block.x[block.count] = x;
                        block.y[block.count] = y;
                        ++block.count;
                    }
                }
                perBlock(block, stats);
            }
        }
    }, context);
    RayStats total;
    statsPerThread.combine_each([&](const RayStats& s) { total += s; });
    return total;
}

// Calls perPixel(x, y, stats) for every pixel of a width x height image; returns the summed stats.
template <class PerPixel>
RayStats forEachPixelInParallel(int width, int height, PerPixel&& perPixel) {
    return forEachPixelBlockInParallel(width, height, [&](const PixelBlock& block, RayStats& stats) {
        for (int k = 0; k < block.count; ++k) perPixel(block.x[k], block.y[k], stats);
    });
}

}  // namespace hybridlab
