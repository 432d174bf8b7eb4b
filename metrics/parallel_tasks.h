#pragma once
// Independent pieces of work (filter passes of different planes) spread over OpenCV's threads:
// one filter pass alone runs on one thread.
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

namespace hybridlab {

inline void runInParallel(const std::vector<std::function<void()>>& tasks) {
    cv::parallel_for_(cv::Range(0, static_cast<int>(tasks.size())), [&](const cv::Range& range) {
        for (int i = range.start; i < range.end; ++i) tasks[i]();
    });
}

}  // namespace hybridlab
