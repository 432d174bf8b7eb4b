// The statistics of the timing protocol (timing_statistics.h) on synthetic timings from a
// fixed-seed noise model: the median's interval covers the true median at its nominal rate, a
// 10% difference is called and a 1% difference is never called, and the round order is the
// documented Williams design.
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/runner/fastest_set.h"
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

TEST(TimingStatistics, ATenPercentDifferenceIsCalledAndOnePercentNever) {
    std::mt19937_64 rng(7);
    int called = 0, calledOnePercent = 0;
    for (int trial = 0; trial < 100; ++trial) {
        // Paired rounds: each round's load multiplies both settings' times alike, plus each
        // frame's own noise.
        // 10 rounds: [x_(2), x_(9)] (with 8, the interval is the whole range, and a 10% difference
        // in 2% noise reaches past 0.97 in about one trial in 10).
        const std::vector<double> load = noisyTimes(rng, 1.0, 0.3, 10);
        std::vector<double> a = noisyTimes(rng, 10.0, 0.02, 10), b = noisyTimes(rng, 11.0, 0.02, 10), c = noisyTimes(rng, 10.1, 0.02, 10);
        for (int k = 0; k < 10; ++k) a[k] *= load[k], b[k] *= load[k], c[k] *= load[k];
        called += compareRatio(pairedRatio(a, b), 0.03) == SpeedOrder::Faster;
        calledOnePercent += compareRatio(pairedRatio(a, c), 0.03) == SpeedOrder::Faster;
        EXPECT_NE(compareRatio(pairedRatio(b, a), 0.03), SpeedOrder::Faster);
    }
    EXPECT_GE(called, 95);
    EXPECT_EQ(calledOnePercent, 0);
}

TEST(TimingStatistics, NoIntervalNoVerdict) {
    EXPECT_EQ(compareRatio(pairedRatio({1, 1, 1}, {2, 2, 2}), 0.03), SpeedOrder::NotDecided);  // 3 rounds: no interval
    EXPECT_EQ(compareRatio(pairedRatio({1, 1, 1, 1, 1, 1}, {2, 2, 2, 2, 2, 2}), 0.03), SpeedOrder::Faster);
    EXPECT_EQ(compareRatio(pairedRatio({2, 2, 2, 2, 2, 2}, {1, 1, 1, 1, 1, 1}), 0.03), SpeedOrder::Slower);
}

TEST(TimingStatistics, RoundsFollowAWilliamsDesign) {
    for (std::size_t n : {2u, 3u, 4u, 5u, 8u, 17u}) {
        SCOPED_TRACE(std::to_string(n) + " settings");
        const std::size_t period = n % 2 ? 2 * n : n;
        std::vector<std::vector<int>> positions(n, std::vector<int>(n, 0)), follows(n, std::vector<int>(n, 0));
        for (std::size_t r = 0; r < period; ++r) {
            const std::vector<std::size_t> order = roundOrder(n, r, 42);
            ASSERT_EQ(std::set<std::size_t>(order.begin(), order.end()).size(), n);
            EXPECT_EQ(roundOrder(n, r, 42), order);          // the same seed, the same order
            EXPECT_EQ(roundOrder(n, r + period, 42), order);  // and again after a period
            for (std::size_t p = 0; p < n; ++p) ++positions[order[p]][p];
            for (std::size_t p = 1; p < n; ++p) ++follows[order[p - 1]][order[p]];
        }
        const int each = n % 2 ? 2 : 1;
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = 0; j < n; ++j) {
                EXPECT_EQ(positions[i][j], each) << "setting " << i << " at position " << j;
                EXPECT_EQ(follows[i][j], i == j ? 0 : each) << j << " right after " << i;
            }
        }
    }
    EXPECT_NE(roundOrder(8, 0, 42), roundOrder(8, 0, 43));
}

TEST(TimingStatistics, SteadyWhenTheLastFramesAgree) {
    EXPECT_FALSE(steadyTimes({50, 30, 20}, 3, 0.1));
    EXPECT_TRUE(steadyTimes({50, 30, 10.2, 10.0, 10.5}, 3, 0.1));
    EXPECT_FALSE(steadyTimes({10, 10}, 3, 0.1));
}

}  // namespace
}  // namespace hybridlab
