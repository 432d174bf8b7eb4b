#include "techniques/heuristic_rt/frame_time_budget.h"

#include <algorithm>

namespace hybridlab {

namespace {
constexpr double kDecay = 0.6;  // weight of the past in the running estimates, per frame
}

double FrameTimeBudget::budget() const { return std::max(target_ - otherMilliseconds_, 0.0) / millisecondsPerCost_; }

void FrameTimeBudget::observe(double costUsed, double rayTracingMilliseconds, double otherMilliseconds) {
    otherMilliseconds_ = observed_ ? kDecay * otherMilliseconds_ + (1.0 - kDecay) * otherMilliseconds : otherMilliseconds;
    observed_ = true;
    if (costUsed <= 0.0) return;
    weightedMilliseconds_ = kDecay * weightedMilliseconds_ + rayTracingMilliseconds;
    weightedCost_ = kDecay * weightedCost_ + costUsed;
    millisecondsPerCost_ = weightedMilliseconds_ / weightedCost_;
}

}  // namespace hybridlab
