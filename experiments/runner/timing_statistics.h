#pragma once
// The statistics of the timing protocol (interleaved_timing.h): the median of a setting's frame
// times with its distribution-free interval, the paired ratio of two settings timed in the same
// rounds, and the order of the settings in each round. The rule that names the fastest settings
// from these is fastest_set.h. The report's Python (report/timing.py) computes the same; tests
// hold the two equal on the same numbers.
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

// The median alone (of at least one value).
double median(std::vector<double> values);

// The rank l (1-based) of the interval's lower end among n sorted values, the upper end being
// n + 1 - l; 0 where no pair reaches `confidence`. The binomial tail is summed in log space, so
// that it holds for any n (2^-n underflows a double from n = 1075).
std::size_t intervalRank(std::size_t n, double confidence = 0.95);

// The smallest n for which a distribution-free interval of the median reaches `confidence`.
std::size_t minimumSamplesForInterval(double confidence = 0.95);

// The paired ratio numerator[k] / denominator[k] over rounds k: its median and interval. Pairing
// the rounds cancels what drifts between rounds (load, clocks): both were timed in the same one.
MedianInterval pairedRatio(const std::vector<double>& numerator, const std::vector<double>& denominator,
                           double confidence = 0.95);

// Round `round`'s order of `count` settings: a Williams design (a Latin square whose every
// setting follows every other equally often: once per `count` rounds for an even count, twice per
// 2 x `count` for an odd one) on the settings relabelled by a permutation drawn from `seed`.
// Every setting is timed at every position equally often, so drift hits them alike, and no setting
// always follows the same neighbour, so what a frame leaves behind (caches, clocks) is spread
// over all of them. The same seed gives the same orders on every run.
std::vector<std::size_t> roundOrder(std::size_t count, std::size_t round, std::uint64_t seed);

// Whether the last `frames` times agree: (max - min) <= tolerance x their median.
bool steadyTimes(const std::vector<double>& times, std::size_t frames, double tolerance);

}  // namespace hybridlab
