#pragma once
// The metrics' parallel loops, on the program's one thread pool (TBB, as the renderers' loops):
// independent pieces of work (filter passes of different planes: one filter pass alone runs on
// one thread) and the rows of an image. Each task and row writes only its own output, so the
// results do not depend on how the work is split.
#include <cstddef>
#include <functional>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace hybridlab {

inline void runInParallel(const std::vector<std::function<void()>>& tasks) {
    tbb::parallel_for(std::size_t{0}, tasks.size(), [&](std::size_t i) { tasks[i](); });
}

// Calls perRow(y) for every y in [0, rows).
template <class PerRow>
void forEachRowInParallel(int rows, PerRow&& perRow) {
    tbb::parallel_for(tbb::blocked_range<int>(0, rows), [&](const tbb::blocked_range<int>& range) {
        for (int y = range.begin(); y < range.end(); ++y) perRow(y);
    });
}

}  // namespace hybridlab
