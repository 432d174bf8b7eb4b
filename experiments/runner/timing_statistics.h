#pragma once
// The statistics of the timing protocol (interleaved_timing.h): the median of a setting's frame
// times with its distribution-free 95% interval, the paired ratio of two settings timed in the
// same rounds, and the rule that calls one faster than another or the two tied. The report's
// Python (report/timing.py) computes the same; tests hold the two equal on the same numbers.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hybridlab {

// A median and its confidence interval [low, high] from the order statistics: the smallest
// symmetric pair x_(l), x_(n+1-l) whose binomial(n, 1/2) coverage reaches the confidence. It holds
// for any continuous distribution of the samples (no normality assumed: frame times are skewed).
// With fewer than 6 samples no such pair reaches 95%, and `hasInterval` is false.
struct MedianInterval {
    double median = 0.0, low = 0.0, high = 0.0;
    std::size_t n = 0;
    bool hasInterval = false;
    // The interval's larger half-width relative to the median: what `precision` bounds.
    double relativeHalfWidth() const;
};
MedianInterval medianInterval(std::vector<double> values, double confidence = 0.95);

// The smallest n for which a distribution-free interval of the median reaches `confidence`.
std::size_t minimumSamplesForInterval(double confidence = 0.95);

// The paired ratio numerator[k] / denominator[k] over rounds k: its median and interval. Pairing
// the rounds cancels what drifts between rounds (load, clocks): both were timed in the same one.
MedianInterval pairedRatio(const std::vector<double>& numerator, const std::vector<double>& denominator);

// A's time against B's from the paired ratio A/B: A is faster only when the ratio's interval lies
// wholly below 1 (beyond the noise) and its median below 1 - tolerance (a difference that
// matters); slower likewise above 1 and 1 + tolerance; else the two are tied.
enum class TimeOrder { Faster, Slower, Tied };
TimeOrder compareTimes(const MedianInterval& ratio, double tolerance);
const char* timeOrderName(TimeOrder order);

// Round `round`'s order of `count` settings: one permutation drawn from `seed`, rotated by one
// place each round, so that over `count` rounds every setting is timed at every position once
// and the same config times in the same order on every run.
std::vector<std::size_t> roundOrder(std::size_t count, std::size_t round, std::uint64_t seed);

// Whether the last `frames` times agree: (max - min) <= tolerance x their median.
bool steadyTimes(const std::vector<double>& times, std::size_t frames, double tolerance);

}  // namespace hybridlab
