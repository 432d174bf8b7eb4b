#include "experiments/runner/interleaved_timing.h"

#include <sched.h>

#include <algorithm>

#include "experiments/runner/fastest_set.h"
#include "experiments/runner/timing_statistics.h"

namespace hybridlab {

namespace {

void warmUp(const TimedRender& render, const TimingProtocol& p, SettingTiming& s) {
    std::vector<double> times;
    const auto done = [&] {
        const int frames = static_cast<int>(times.size());
        if (frames < p.warmupFrames || s.warmupMs < p.warmupMs) return false;
        if (p.warmupFrames == 0 || frames >= p.maxWarmupFrames) return true;
        return steadyTimes(times, static_cast<std::size_t>(std::max(p.steadyFrames, 1)), p.steadyTolerance);
    };
    while (!done()) {
        const FrameClocks c = render();
        times.push_back(c.wallMs);
        s.warmupMs += c.wallMs;
    }
    s.warmupFrames = static_cast<int>(times.size());
    s.steady = p.warmupFrames > 0 && (p.steadyFrames <= 0 || steadyTimes(times, static_cast<std::size_t>(p.steadyFrames), p.steadyTolerance));
}

bool precisionReached(const GroupTiming& g, double precision) {
    return std::all_of(g.settings.begin(), g.settings.end(), [&](const SettingTiming& s) {
        return medianInterval(wallTimes(s)).relativeHalfWidth() <= precision;
    });
}

}  // namespace

double budgetCost(const FrameClocks& c, const TimingProtocol& p) {
    return p.budgetClock == BudgetClock::CpuPerCore ? c.cpuMs / std::max(p.cores, 1) : c.wallMs;
}

int usableCores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) != 0) return 1;
    return std::max(CPU_COUNT(&set), 1);
}

std::vector<double> wallTimes(const SettingTiming& s) {
    std::vector<double> v;
    for (const FrameClocks& c : s.rounds) v.push_back(c.wallMs);
    return v;
}

std::vector<double> cpuTimes(const SettingTiming& s) {
    std::vector<double> v;
    for (const FrameClocks& c : s.rounds) v.push_back(c.cpuMs);
    return v;
}

std::optional<std::vector<double>> deviceTimes(const SettingTiming& s) {
    std::vector<double> v;
    for (const FrameClocks& c : s.rounds) {
        if (!c.deviceMs) return std::nullopt;
        v.push_back(*c.deviceMs);
    }
    return v.empty() ? std::nullopt : std::optional(v);
}

GroupTiming timeInterleaved(const std::vector<TimedRender>& settings, const TimingProtocol& p) {
    GroupTiming g;
    g.budgetClock = p.budgetClock;
    g.settings.resize(settings.size());
    for (std::size_t i = 0; i < settings.size(); ++i) warmUp(settings[i], p, g.settings[i]);
    // Fewer rounds than an interval needs: exactly those (a quick check, a test), no more.
    const bool quick = p.minRounds < static_cast<int>(minimumSamplesForInterval());
    const int maxRounds = quick ? std::max(p.minRounds, 1) : std::max(p.maxRounds, p.minRounds);
    const int decision = static_cast<int>(roundsForDecision(static_cast<std::size_t>(std::max(p.settingsCompared, 0))));
    const int minRounds = quick ? maxRounds : std::min(std::max(p.minRounds, decision), maxRounds);
    while (g.rounds < maxRounds) {
        if (g.rounds >= minRounds) {
            g.precisionReached = precisionReached(g, p.precision);
            if (g.precisionReached || g.budgetSpentMs >= p.groupBudgetMs) break;
        }
        for (std::size_t i : roundOrder(settings.size(), static_cast<std::size_t>(g.rounds), p.seed)) {
            const FrameClocks c = settings[i]();
            g.settings[i].rounds.push_back(c);
            g.roundsMs += c.wallMs;
            g.budgetSpentMs += budgetCost(c, p);
        }
        ++g.rounds;
    }
    if (g.rounds >= maxRounds) g.precisionReached = precisionReached(g, p.precision);
    return g;
}

GroupTiming timeSequential(const std::vector<TimedRender>& settings, const TimingProtocol& p, int rounds) {
    GroupTiming g;
    g.settings.resize(settings.size());
    g.rounds = rounds;
    for (std::size_t i = 0; i < settings.size(); ++i) {
        warmUp(settings[i], p, g.settings[i]);
        for (int k = 0; k < rounds; ++k) {
            g.settings[i].rounds.push_back(settings[i]());
            g.roundsMs += g.settings[i].rounds.back().wallMs;
            g.budgetSpentMs += budgetCost(g.settings[i].rounds.back(), p);
        }
    }
    g.precisionReached = precisionReached(g, p.precision);
    return g;
}

}  // namespace hybridlab
