// The statistics of the timing protocol (timing_statistics.h) on synthetic timings from a
// fixed-seed noise model: the median's interval covers the true median at its nominal rate, a
// 10% difference is called and a 1% difference is a tie, and the round order is the documented one.
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/runner/timing_statistics.h"

namespace hybridlab {
namespace {

// Frame times around `median` with multiplicative, right-skewed noise (log-normal: a frame is
// slowed more often and further than it is sped up, as load does); exp(0) = 1 is its median.
std::vector<double> noisyTimes(std::mt19937_64& rng, double median, double sigma, int n) {
    std::normal_distribution<double> normal(0.0, sigma);
    std::vector<double> v;
    for (int i = 0; i < n; ++i) v.push_back(median * std::exp(normal(rng)));
    return v;
}

TEST(TimingStatistics, TheIntervalIsThePairOfOrderStatisticsThatReaches95Percent) {
    EXPECT_EQ(minimumSamplesForInterval(), 6u);  // 1 - 2 / 2^6 = 0.969; with 5, 0.9375
    EXPECT_FALSE(medianInterval({5, 1, 4, 2, 3}).hasInterval);
    const MedianInterval six = medianInterval({6, 1, 5, 2, 4, 3});
    EXPECT_TRUE(six.hasInterval);
    EXPECT_DOUBLE_EQ(six.median, 3.5);
    EXPECT_DOUBLE_EQ(six.low, 1.0);
    EXPECT_DOUBLE_EQ(six.high, 6.0);
    // n = 10: [x_(2), x_(9)] covers 1 - 2 P(X <= 1) = 0.979; [x_(3), x_(8)] only 0.891.
    const MedianInterval ten = medianInterval({10, 9, 8, 7, 6, 5, 4, 3, 2, 1});
    EXPECT_DOUBLE_EQ(ten.low, 2.0);
    EXPECT_DOUBLE_EQ(ten.high, 9.0);
    // n = 20: [x_(6), x_(15)] covers 0.959.
    std::vector<double> twenty(20);
    for (int i = 0; i < 20; ++i) twenty[i] = i + 1;
    const MedianInterval t = medianInterval(twenty);
    EXPECT_DOUBLE_EQ(t.low, 6.0);
    EXPECT_DOUBLE_EQ(t.high, 15.0);
    EXPECT_NEAR(t.relativeHalfWidth(), (15.0 - 10.5) / 10.5, 1e-12);
}

TEST(TimingStatistics, TheIntervalCoversTheTrueMedianAtItsNominalRate) {
    std::mt19937_64 rng(20261127);
    for (int n : {6, 12, 20}) {
        int covered = 0;
        const int draws = 1000;
        for (int d = 0; d < draws; ++d) {
            const MedianInterval m = medianInterval(noisyTimes(rng, 10.0, 0.2, n));
            covered += m.low <= 10.0 && 10.0 <= m.high;
        }
        // Exact coverage: 0.969 (n = 6), 0.961 (12), 0.959 (20); about 95 of 100 draws.
        EXPECT_GE(covered, 930) << n << " samples";
        EXPECT_LE(covered, 990) << n << " samples";
    }
}

TEST(TimingStatistics, ATenPercentDifferenceIsCalledAndOnePercentIsATie) {
    std::mt19937_64 rng(7);
    int called = 0, tied = 0;
    for (int trial = 0; trial < 100; ++trial) {
        // Paired rounds: each round's load multiplies both settings' times alike, plus each
        // frame's own noise.
        const std::vector<double> load = noisyTimes(rng, 1.0, 0.3, 8);
        std::vector<double> a = noisyTimes(rng, 10.0, 0.02, 8), b = noisyTimes(rng, 11.0, 0.02, 8), c = noisyTimes(rng, 10.1, 0.02, 8);
        for (int k = 0; k < 8; ++k) a[k] *= load[k], b[k] *= load[k], c[k] *= load[k];
        called += compareTimes(pairedRatio(a, b), 0.03) == TimeOrder::Faster;
        tied += compareTimes(pairedRatio(a, c), 0.03) == TimeOrder::Tied;
        EXPECT_NE(compareTimes(pairedRatio(b, a), 0.03), TimeOrder::Faster);
    }
    EXPECT_GE(called, 95);
    EXPECT_GE(tied, 95);
}

TEST(TimingStatistics, NoIntervalNoVerdict) {
    EXPECT_EQ(compareTimes(pairedRatio({1, 1, 1}, {2, 2, 2}), 0.03), TimeOrder::Tied);  // 3 rounds: no interval
    EXPECT_EQ(compareTimes(pairedRatio({1, 1, 1, 1, 1, 1}, {2, 2, 2, 2, 2, 2}), 0.03), TimeOrder::Faster);
    EXPECT_EQ(compareTimes(pairedRatio({2, 2, 2, 2, 2, 2}, {1, 1, 1, 1, 1, 1}), 0.03), TimeOrder::Slower);
}

TEST(TimingStatistics, EachRoundRotatesOneSeededPermutationByOnePlace) {
    const std::size_t n = 5;
    const std::vector<std::size_t> first = roundOrder(n, 0, 42);
    EXPECT_EQ(std::set<std::size_t>(first.begin(), first.end()).size(), n);
    std::vector<std::set<std::size_t>> positions(n);
    for (std::size_t r = 0; r < n; ++r) {
        const std::vector<std::size_t> order = roundOrder(n, r, 42);
        std::vector<std::size_t> rotated = first;
        std::rotate(rotated.begin(), rotated.begin() + static_cast<std::ptrdiff_t>(r), rotated.end());
        EXPECT_EQ(order, rotated) << "round " << r;
        for (std::size_t p = 0; p < n; ++p) positions[order[p]].insert(p);
        EXPECT_EQ(roundOrder(n, r, 42), order);  // the same seed, the same order
    }
    for (const auto& at : positions) EXPECT_EQ(at.size(), n);  // every setting at every position once
    EXPECT_EQ(roundOrder(n, n, 42), first);
    EXPECT_NE(roundOrder(8, 0, 42), roundOrder(8, 0, 43));
}

TEST(TimingStatistics, SteadyWhenTheLastFramesAgree) {
    EXPECT_FALSE(steadyTimes({50, 30, 20}, 3, 0.1));
    EXPECT_TRUE(steadyTimes({50, 30, 10.2, 10.0, 10.5}, 3, 0.1));
    EXPECT_FALSE(steadyTimes({10, 10}, 3, 0.1));
}

}  // namespace
}  // namespace hybridlab
