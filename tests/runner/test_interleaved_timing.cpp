// The timing protocol (interleaved_timing.h) on synthetic settings whose frame times come from a
// virtual clock: the order the frames run in, the warm-up to a steady state, the stopping rule,
// and what interleaving buys under a drifting load.
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/runner/interleaved_timing.h"
#include "experiments/runner/timing_statistics.h"

namespace hybridlab {
namespace {

// Settings sharing one virtual clock: each frame's time is the setting's own cost times the load
// at the clock's time (the machine's, which drifts), times the frame's own noise.
struct VirtualMachine {
    double now = 0.0;
    std::function<double(double)> load = [](double) { return 1.0; };
    std::mt19937_64 rng{1};
    double noise = 0.0;
    std::vector<int> calls;

    TimedRender setting(int id, double cost, std::vector<double> firstFrames = {}) {
        return [this, id, cost, firstFrames, frame = std::size_t{0}]() mutable {
            calls.push_back(id);
            double t = frame < firstFrames.size() ? firstFrames[frame] : cost;
            ++frame;
            t *= load(now) * std::exp(std::normal_distribution<double>(0.0, noise)(rng));
            now += t;
            return FrameClocks{t, t, std::nullopt};
        };
    }
};

TEST(InterleavedTiming, RoundsRunEverySettingOnceInTheDocumentedOrder) {
    VirtualMachine m;
    TimingProtocol p;
    p.warmupFrames = 0;
    p.steadyFrames = 0;
    p.maxWarmupFrames = 0;
    p.minRounds = 7;
    p.maxRounds = 7;
    const GroupTiming g = timeInterleaved({m.setting(0, 1), m.setting(1, 2), m.setting(2, 3)}, p);
    EXPECT_EQ(g.rounds, 7);
    ASSERT_EQ(m.calls.size(), 21u);
    for (std::size_t r = 0; r < 7; ++r) {
        const std::vector<std::size_t> order = roundOrder(3, r, p.seed);
        for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(m.calls[r * 3 + k], static_cast<int>(order[k])) << "round " << r;
    }
    for (const SettingTiming& s : g.settings) EXPECT_EQ(s.rounds.size(), 7u);
}

TEST(InterleavedTiming, WarmUpGoesOnUntilTheLastFramesAgree) {
    VirtualMachine m;
    TimingProtocol p;
    p.warmupFrames = 1;  // 1 frame, then until 3 agree within 10%, at most 10
    p.steadyFrames = 3;
    p.steadyTolerance = 0.1;
    p.maxWarmupFrames = 10;
    const GroupTiming g = timeInterleaved({m.setting(0, 10, {80, 40, 20, 12}), m.setting(1, 5, {90, 80, 70, 60, 50, 40, 30, 20, 10, 9, 8})}, p);
    // 80 40 20 12 10 10: the last three, 12 10 10, still differ by 20%; the seventh frame agrees.
    EXPECT_EQ(g.settings[0].warmupFrames, 7);
    EXPECT_TRUE(g.settings[0].steady);
    EXPECT_DOUBLE_EQ(g.settings[0].warmupMs, 80 + 40 + 20 + 12 + 10 + 10 + 10);
    EXPECT_EQ(g.settings[1].warmupFrames, 10);  // the cap
    EXPECT_FALSE(g.settings[1].steady);
}

TEST(InterleavedTiming, RoundsStopAtThePrecisionOrTheBudget) {
    TimingProtocol p;
    {
        VirtualMachine m;  // no noise: the interval is the median itself after the fewest rounds
        const GroupTiming g = timeInterleaved({m.setting(0, 10), m.setting(1, 20)}, p);
        EXPECT_EQ(g.rounds, 6);
        EXPECT_TRUE(g.precisionReached);
    }
    {
        VirtualMachine m;
        m.noise = 0.5;
        p.groupBudgetMs = 1e12;
        p.maxRounds = 40;
        const GroupTiming g = timeInterleaved({m.setting(0, 10), m.setting(1, 20)}, p);
        EXPECT_EQ(g.rounds, 40);
        EXPECT_FALSE(g.precisionReached);
    }
    {
        VirtualMachine m;
        m.noise = 0.5;
        p.groupBudgetMs = 300;  // 30 ms a round: past the budget after 10 rounds
        const GroupTiming g = timeInterleaved({m.setting(0, 10), m.setting(1, 20)}, p);
        EXPECT_GE(g.rounds, 6);
        EXPECT_LE(g.rounds, 14);
        EXPECT_GE(g.roundsMs, 300);
    }
}

TEST(InterleavedTiming, RoundsEnoughForTheVerdictToTellTheFastestApart) {
    // 16 settings: each comparison with the fastest at 1 - 0.05 / 15 needs 10 paired rounds.
    // Noise-free frames reach the precision at once; the rounds go on to 10 all the same.
    TimingProtocol p;
    p.warmupFrames = 0;
    p.settingsCompared = 16;
    const auto sixteen = [](VirtualMachine& m) {
        std::vector<TimedRender> settings;
        for (int i = 0; i < 16; ++i) settings.push_back(m.setting(i, 10.0 + i));
        return settings;
    };
    {
        VirtualMachine m;
        EXPECT_EQ(timeInterleaved(sixteen(m), p).rounds, 10);
    }
    {
        VirtualMachine m;  // within max_rounds
        p.maxRounds = 8;
        EXPECT_EQ(timeInterleaved(sixteen(m), p).rounds, 8);
    }
    {
        VirtualMachine m;  // repeats below 6: exactly those, and the report decides nothing
        p.minRounds = 3;
        EXPECT_EQ(timeInterleaved(sixteen(m), p).rounds, 3);
    }
}

TEST(InterleavedTiming, OnTheCpuClockALoadedMachineTimesAsManyRoundsAsAnIdleOne) {
    // Frames of two threads' work: 20 ms of CPU time, 10 ms of wall time on two idle cores, 40 ms
    // with another process's load (a thread preempted in a parallel frame waits its turn).
    // Every other frame 20% slower, so that the precision is never reached and the budget ends
    // the rounds.
    const auto frames = [](double wallMs) {
        const auto setting = [wallMs, k = 0]() mutable { return FrameClocks{wallMs * (k++ % 2 ? 1.2 : 1.0), 20.0, std::nullopt}; };
        return std::vector<TimedRender>{setting, setting};
    };
    TimingProtocol p;
    p.warmupFrames = 0;
    p.maxRounds = 100;
    p.groupBudgetMs = 400;
    p.cores = 2;
    p.budgetClock = BudgetClock::CpuPerCore;
    const GroupTiming idle = timeInterleaved(frames(10.0), p), loaded = timeInterleaved(frames(40.0), p);
    EXPECT_EQ(idle.rounds, 20);  // 2 frames x 20 ms / 2 cores a round
    EXPECT_EQ(loaded.rounds, idle.rounds);
    EXPECT_DOUBLE_EQ(loaded.roundsMs, 4 * idle.roundsMs);
    EXPECT_EQ(loaded.budgetClock, BudgetClock::CpuPerCore);
    p.budgetClock = BudgetClock::Wall;  // on a GPU: the load costs rounds
    EXPECT_EQ(timeInterleaved(frames(10.0), p).rounds, 19);  // 22 ms a round
    EXPECT_EQ(timeInterleaved(frames(40.0), p).rounds, 6);   // the fewest, 88 ms a round
    EXPECT_GE(usableCores(), 1);
}

TEST(InterleavedTiming, ADriftingLoadChangesARatioFarLessInterleavedThanSequential) {
    // Two settings of equal cost while the machine's load doubles over the experiment (another
    // job starting): timed one after the other, the second looks slower; interleaved, the ratio
    // stays near 1.
    const auto ratioError = [](bool interleaved) {
        VirtualMachine m;
        m.noise = 0.01;
        m.load = [](double t) { return 1.0 + t / 300.0; };
        TimingProtocol p;
        p.minRounds = 10;
        p.maxRounds = 10;
        const std::vector<TimedRender> settings = {m.setting(0, 10), m.setting(1, 10)};
        const GroupTiming g = interleaved ? timeInterleaved(settings, p) : timeSequential(settings, p, 10);
        return std::abs(pairedRatio(wallTimes(g.settings[1]), wallTimes(g.settings[0])).median - 1.0);
    };
    const double interleaved = ratioError(true), sequential = ratioError(false);
    EXPECT_GT(sequential, 0.2);
    EXPECT_LT(interleaved, 0.05);
    EXPECT_LT(interleaved, sequential / 5.0);
}

}  // namespace
}  // namespace hybridlab
