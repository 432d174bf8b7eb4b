#pragma once
// Wall-clock timing of a frame's stages into FrameResult::stages.
#include <chrono>
#include <string>

#include "techniques/technique.h"

namespace hybridlab {

class StageClock {
public:
    explicit StageClock(FrameResult& result) : result_(result), start_(std::chrono::steady_clock::now()) {}

    // Ends the current stage under `name` and starts the next.
    void lap(const std::string& name) {
        auto now = std::chrono::steady_clock::now();
        result_.stages.push_back({name, std::chrono::duration<double, std::milli>(now - start_).count()});
        start_ = now;
    }

private:
    FrameResult& result_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace hybridlab
