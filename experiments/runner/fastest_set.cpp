#include "experiments/runner/fastest_set.h"

#include <algorithm>
#include <map>
#include <utility>
#include <stdexcept>

namespace hybridlab {

namespace {

bool insideBand(const MedianInterval& ratio, double tolerance) {
    return ratio.low >= 1.0 - tolerance && ratio.high <= 1.0 / (1.0 - tolerance);
}

}  // namespace

const char* speedOrderName(SpeedOrder order) {
    switch (order) {
        case SpeedOrder::Faster: return "faster";
        case SpeedOrder::Slower: return "slower";
        case SpeedOrder::Tied: return "tied";
        case SpeedOrder::NotDecided: return "not decided";
    }
    return "?";
}

const char* fastestDecisionName(FastestDecision decision) {
    switch (decision) {
        case FastestDecision::Single: return "single";
        case FastestDecision::Tied: return "tied";
        case FastestDecision::NotDecided: return "not decided";
    }
    return "?";
}

SpeedOrder compareRatio(const MedianInterval& ratio, double tolerance) {
    if (!ratio.hasInterval) return SpeedOrder::NotDecided;
    if (ratio.high < 1.0 - tolerance) return SpeedOrder::Faster;
    if (ratio.low > 1.0 / (1.0 - tolerance)) return SpeedOrder::Slower;
    return insideBand(ratio, tolerance) ? SpeedOrder::Tied : SpeedOrder::NotDecided;
}

std::vector<double> pairedRatios(const SettingRounds& a, const SettingRounds& b) {
    std::map<std::string, const std::vector<double>*> theirs;
    for (const TimingRounds& t : b.timings) theirs[t.timingId] = &t.ms;
    std::map<std::string, const std::vector<double>*> ours;
    for (const TimingRounds& t : a.timings) ours[t.timingId] = &t.ms;
    std::vector<double> ratios;
    for (const auto& [id, mine] : ours) {
        const auto other = theirs.find(id);
        if (other == theirs.end() || other->second->size() != mine->size()) continue;
        for (std::size_t k = 0; k < mine->size(); ++k)
            if ((*mine)[k] > 0.0 && (*other->second)[k] > 0.0) ratios.push_back((*mine)[k] / (*other->second)[k]);
    }
    return ratios;
}

double settingTime(const SettingRounds& s) {
    std::vector<double> medians;
    for (const TimingRounds& t : s.timings)
        if (!t.ms.empty()) medians.push_back(median(t.ms));
    if (medians.empty()) throw std::invalid_argument("settingTime: setting '" + s.name + "' has no rounds");
    return median(std::move(medians));
}

SpeedOrder compareSettings(const SettingRounds& a, const SettingRounds& b, double tolerance, double confidence) {
    std::vector<double> ratios = pairedRatios(a, b);
    if (ratios.empty()) return SpeedOrder::NotDecided;
    const SpeedOrder byRounds = compareRatio(medianInterval(std::move(ratios), confidence), tolerance);
    const double times = settingTime(a) / settingTime(b);
    const bool timesAgree = byRounds == SpeedOrder::Faster   ? times < 1.0 - tolerance
                            : byRounds == SpeedOrder::Slower ? times > 1.0 / (1.0 - tolerance)
                            : byRounds == SpeedOrder::Tied   ? times >= 1.0 - tolerance && times <= 1.0 / (1.0 - tolerance)
                                                             : true;
    return timesAgree ? byRounds : SpeedOrder::NotDecided;
}

double comparisonConfidence(std::size_t settings, double familyConfidence) {
    return settings <= 2 ? familyConfidence : 1.0 - (1.0 - familyConfidence) / static_cast<double>(settings - 1);
}

std::size_t roundsForDecision(std::size_t settings, double familyConfidence) {
    return settings <= 1 ? 0 : minimumSamplesForInterval(comparisonConfidence(settings, familyConfidence));
}

FastestSet fastestSet(const std::vector<SettingRounds>& settings, double tolerance, double familyConfidence) {
    if (settings.empty()) throw std::invalid_argument("fastestSet of no settings");
    FastestSet out;
    std::vector<double> times;
    for (const SettingRounds& s : settings) times.push_back(settingTime(s));
    out.best = static_cast<std::size_t>(std::min_element(times.begin(), times.end()) - times.begin());
    const double confidence = comparisonConfidence(settings.size(), familyConfidence);
    bool allTied = true;
    for (std::size_t i = 0; i < settings.size(); ++i) {
        if (i == out.best) {
            out.members.push_back(i);
            continue;
        }
        if (pairedRatios(settings[i], settings[out.best]).empty()) {
            out.members.push_back(i);
            ++out.unpaired;
            allTied = false;
            continue;
        }
        const SpeedOrder order = compareSettings(settings[i], settings[out.best], tolerance, confidence);
        if (order == SpeedOrder::Slower) continue;
        out.members.push_back(i);
        allTied &= order == SpeedOrder::Tied;
    }
    out.decision = out.members.size() == 1 ? FastestDecision::Single : allTied ? FastestDecision::Tied : FastestDecision::NotDecided;
    return out;
}

}  // namespace hybridlab
