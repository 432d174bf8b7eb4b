#pragma once
// The timing protocol of an experiment (experiments/README.md "Timing"): the settings compared
// with each other (one scene, view, frame and size: a group) are timed in interleaved rounds, so
// that drift in the machine's load or a GPU's clock hits every setting alike.
//
//   1. Warm-up, each setting in turn: `warmup_frames` frames (and more until `warmup_ms`), then on
//      until the last `steady_frames` frames agree within `steady_tolerance`, or
//      `max_warmup_frames` frames in all. `warmup_frames = 0`: no warm-up at all.
//   2. Rounds: every setting once a round, in roundOrder's order (timing_statistics.h). At least
//      `repeats` rounds, then more until every setting's median has a 95% interval within
//      +-`precision` of itself, or the rounds have taken the group's share of `budget_s`, or
//      `max_rounds`. On a CPU (Embree, lavapipe) the budget counts the process's CPU time over
//      the cores it may use, what its frames take on an idle machine: other processes' load
//      stretches the frames' wall time (a parallel frame waits for its preempted thread) but not
//      their CPU time, so a loaded machine times as many rounds as an idle one and its intervals
//      are no wider for want of rounds. On a GPU the budget counts wall time. The budget is for
//      one scene and size, shared equally by its groups (its views and frames): the report pools
//      a setting's rounds over them, so a scene seen from one view gets as many rounds to rank its
//      settings as one seen along a path. With `repeats` below 6, too few for a 95% interval of a
//      median, exactly `repeats` rounds and no interval (quick checks and tests).
//
// Nothing else runs between a group's frames: scoring and files come after its rounds.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace hybridlab {

// The three clocks of one frame.
struct FrameClocks {
    double wallMs = 0.0;                  // what a user waits: the frame's stages, which cover its wall clock
    double cpuMs = 0.0;                   // this process's CPU time, all threads
    std::optional<double> deviceMs;       // the device's own timestamps of the frame's device work, where it has them
};

// What the budget counts (see above).
enum class BudgetClock { Wall, CpuPerCore };

struct TimingProtocol {
    int warmupFrames = 1;
    double warmupMs = 0.0;
    int steadyFrames = 2;
    double steadyTolerance = 0.1;
    int maxWarmupFrames = 5;
    int minRounds = 6;  // `repeats`
    int maxRounds = 30;
    int settingsCompared = 0;  // the group's settings the verdict compares (the reference not among them)
    double precision = 0.03;
    double groupBudgetMs = 2000.0;  // the runner's share of `budget_s` for one group (see below)
    double sceneBudgetMs = 6000.0;  // `budget_s`: for one scene and size, shared by its groups
    BudgetClock budgetClock = BudgetClock::Wall;
    int cores = 1;                  // what CpuPerCore divides by: the cores the process may run on
    std::uint64_t seed = 0x68796272696c6162ULL;  // "hybrilab": one fixed order for every run
};

struct SettingTiming {
    std::vector<FrameClocks> rounds;  // round k's frame at [k]
    int warmupFrames = 0;
    double warmupMs = 0.0;            // the warm-up's frames, by their wall clocks
    bool steady = false;              // the warm-up ended on agreeing frames, not on its cap
};

struct GroupTiming {
    std::vector<SettingTiming> settings;  // in the order given
    int rounds = 0;
    bool precisionReached = false;        // every setting's wall-time interval within the precision
    double roundsMs = 0.0;                // the rounds' frames, by their wall clocks
    double budgetSpentMs = 0.0;           // the rounds' frames, by the budget's clock
    BudgetClock budgetClock = BudgetClock::Wall;
};

// Renders one frame of a setting and returns its clocks.
using TimedRender = std::function<FrameClocks()>;

// Times `settings` by the protocol. The budget counts the frames' own clocks (not a clock read
// around them), so that a synthetic clock in the tests sees the protocol exactly as a real one.
GroupTiming timeInterleaved(const std::vector<TimedRender>& settings, const TimingProtocol& protocol);

// The same frames timed one setting after another (all of A's rounds, then B's, ...): what the
// runner did before interleaving, kept for the tests that measure what interleaving buys.
GroupTiming timeSequential(const std::vector<TimedRender>& settings, const TimingProtocol& protocol, int rounds);

// One frame's cost against the budget, by the protocol's budget clock.
double budgetCost(const FrameClocks& c, const TimingProtocol& protocol);

// The cores this process may run on (its CPU affinity), at least 1.
int usableCores();

std::vector<double> wallTimes(const SettingTiming& s);
std::vector<double> cpuTimes(const SettingTiming& s);
std::optional<std::vector<double>> deviceTimes(const SettingTiming& s);  // none unless every round has one

}  // namespace hybridlab
