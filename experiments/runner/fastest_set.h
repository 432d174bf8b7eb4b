#pragma once
// The rule that names the fastest settings, and says whether one setting is faster than another,
// from their times in paired rounds (experiments/README.md "Timing"). report/timing.py holds the
// same rule in Python; tests/fixtures/fastest_set_cases.json is a table of cases both must answer
// alike (tests/runner/test_fastest_set.cpp, tests/report/timing_test.py).
//
// Rounds pair only within one timing: the rounds one call of the runner timed a group in (a
// record's `timing.timing_id`). Two settings timed in different processes, shards or resumed
// runs have no rounds in common, however many each has.
//
// Faster: A is faster than B when the interval of the median of the paired ratios A_k / B_k lies
// wholly below 1 - tolerance, and A's time (the median over its timings of its median in each:
// the time the report shows) is below 1 - tolerance of B's; slower likewise beyond
// 1 / (1 - tolerance) (the same band in log space); tied when the interval and the ratio of the
// times lie inside [1 - tolerance, 1 / (1 - tolerance)]; otherwise, or without an interval (too
// few paired rounds), not decided. The times' condition matters where rounds of several views or
// frames are pooled: per frame the settings may differ while over the frames they take the same
// time (A faster on one frame, B on the next: the pooled ratios' medians need not compose, and
// A, B, C can each beat the next), and then neither is named faster.
//
// The fastest set: a confidence set for the fastest setting. The empirical best (the lowest time:
// the median over its timings of its median in each) is compared with every other setting, each
// comparison at 1 - 0.05 / (k - 1) (Bonferroni over the k - 1 comparisons); a setting leaves the
// set only when the best is faster than it by that interval. The true fastest leaves only when
// some setting beats it in one of its k - 1 comparisons, so the set holds it with probability at
// least 95%, whatever the empirical best was. A set of one is a decision; a larger one is tied
// when every other member's interval lies inside the band, and not decided otherwise.
#include <cstddef>
#include <string>
#include <vector>

#include "experiments/runner/timing_statistics.h"

namespace hybridlab {

// A against B.
enum class SpeedOrder { Faster, Slower, Tied, NotDecided };
const char* speedOrderName(SpeedOrder order);  // "faster", "slower", "tied", "not decided"

// The ratio A/B's interval against the band [1 - tolerance, 1 / (1 - tolerance)] (a speed-up's,
// where there is no time of the other to compare with).
SpeedOrder compareRatio(const MedianInterval& ratio, double tolerance);

// One timing's rounds of one setting: `timingId` names the runner's call that timed them.
struct TimingRounds {
    std::string timingId;
    std::vector<double> ms;  // the frame time in round k at [k]
};

// A setting's rounds over every timing it was in (its runs: views, frames of a path).
struct SettingRounds {
    std::string name;
    std::vector<TimingRounds> timings;
};

// A_k / B_k over the rounds of every timing both were in (timings in id order); none across two
// timings.
std::vector<double> pairedRatios(const SettingRounds& a, const SettingRounds& b);

// The median over a setting's timings of its median in each (the report's setting time).
double settingTime(const SettingRounds& s);

// A against B at `confidence`, paired within timings, and their times (see above).
SpeedOrder compareSettings(const SettingRounds& a, const SettingRounds& b, double tolerance, double confidence = 0.95);

enum class FastestDecision { Single, Tied, NotDecided };
const char* fastestDecisionName(FastestDecision decision);  // "single", "tied", "not decided"

struct FastestSet {
    std::vector<std::size_t> members;  // indices into the settings, in their order
    std::size_t best = 0;              // the empirical best (the first of equal times)
    FastestDecision decision = FastestDecision::Single;
    std::size_t unpaired = 0;          // members kept because they share no round with the best
};

// The confidence each of the comparisons with the best is made at, among `settings`.
double comparisonConfidence(std::size_t settings, double familyConfidence = 0.95);

// The fewest paired rounds with which the best can be told apart from each of `settings` - 1
// others (no interval below it): 6 for two settings, 10 for 16.
std::size_t roundsForDecision(std::size_t settings, double familyConfidence = 0.95);

// The fastest set of `settings` (at least one).
FastestSet fastestSet(const std::vector<SettingRounds>& settings, double tolerance, double familyConfidence = 0.95);

}  // namespace hybridlab
