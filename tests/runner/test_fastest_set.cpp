// The rule that names the fastest settings (fastest_set.h) on the cases of
// tests/fixtures/fastest_set_cases.json, which report/timing.py answers too
// (tests/report/timing_test.py): the two sides cannot drift apart.
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "experiments/runner/fastest_set.h"
#include "experiments/runner/timing_statistics.h"

namespace hybridlab {
namespace {

nlohmann::json cases() {
    std::ifstream in(std::string(HYBRIDLAB_TEST_FIXTURES) + "/fastest_set_cases.json");
    return nlohmann::json::parse(in);
}

std::vector<SettingRounds> settingsOf(const nlohmann::json& c) {
    std::vector<SettingRounds> out;
    for (const auto& s : c.at("settings")) {
        SettingRounds setting{s.at("name").get<std::string>(), {}};
        for (const auto& [id, ms] : s.at("timings").items()) setting.timings.push_back({id, ms.get<std::vector<double>>()});
        out.push_back(std::move(setting));
    }
    return out;
}

const SettingRounds& named(const std::vector<SettingRounds>& settings, const std::string& name) {
    for (const SettingRounds& s : settings)
        if (s.name == name) return s;
    throw std::runtime_error("no setting " + name);
}

TEST(FastestSet, EveryCaseOfTheSharedTable) {
    const nlohmann::json table = cases();
    ASSERT_GE(table.at("fastest_set").size(), 10u);
    for (const auto& c : table.at("fastest_set")) {
        SCOPED_TRACE(c.at("name").get<std::string>());
        const std::vector<SettingRounds> settings = settingsOf(c);
        const double tolerance = c.at("tolerance").get<double>();
        const FastestSet set = fastestSet(settings, tolerance);
        std::vector<std::string> members;
        for (std::size_t i : set.members) members.push_back(settings[i].name);
        const auto& expected = c.at("expected");
        EXPECT_EQ(members, expected.at("members").get<std::vector<std::string>>());
        EXPECT_EQ(settings[set.best].name, expected.at("best").get<std::string>());
        EXPECT_EQ(fastestDecisionName(set.decision), expected.at("decision").get<std::string>());
        EXPECT_EQ(set.unpaired, expected.at("unpaired").get<std::size_t>());
        for (const auto& pair : c.at("pairs")) {
            const std::string a = pair.at(0), b = pair.at(1), order = pair.at(2);
            EXPECT_EQ(speedOrderName(compareSettings(named(settings, a), named(settings, b), tolerance)), order) << a << " against " << b;
        }
    }
}

TEST(FastestSet, IntervalRanksAndRoundsOfTheSharedTable) {
    const nlohmann::json table = cases();
    for (const auto& r : table.at("interval_ranks")) {
        const std::size_t n = r.at("n");
        EXPECT_EQ(intervalRank(n, r.at("confidence").get<double>()), r.at("rank").get<std::size_t>()) << n << " values";
    }
    for (const auto& r : table.at("rounds_for_decision"))
        EXPECT_EQ(roundsForDecision(r.at("settings").get<std::size_t>()), r.at("rounds").get<std::size_t>()) << r.dump();
}

TEST(FastestSet, TheIntervalOf2000RoundsIsNoWiderThanTheRanksSay) {
    // 2^-2000 is 0 as a double: without log space every term vanished and the interval collapsed
    // to the median. Values 1..2000: the interval is [x_(956), x_(1045)].
    std::vector<double> values(2000);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<double>(values.size() - i);
    const MedianInterval m = medianInterval(values);
    ASSERT_TRUE(m.hasInterval);
    EXPECT_DOUBLE_EQ(m.median, 1000.5);
    EXPECT_DOUBLE_EQ(m.low, 956.0);
    EXPECT_DOUBLE_EQ(m.high, 1045.0);
}

TEST(FastestSet, TheBandIsSymmetricInLogSpace) {
    MedianInterval r;
    r.hasInterval = true;
    r.median = r.low = r.high = 0.969;
    EXPECT_EQ(compareRatio(r, 0.03), SpeedOrder::Faster);
    r.median = r.low = r.high = 1.0 / 0.969;
    EXPECT_EQ(compareRatio(r, 0.03), SpeedOrder::Slower);
    r.low = 0.971, r.high = 1.03;
    EXPECT_EQ(compareRatio(r, 0.03), SpeedOrder::Tied);
    r.low = 0.96, r.high = 0.98;  // straddles 1 - tolerance: too wide to tell
    EXPECT_EQ(compareRatio(r, 0.03), SpeedOrder::NotDecided);
    r.hasInterval = false;
    r.low = r.high = 0.5;
    EXPECT_EQ(compareRatio(r, 0.03), SpeedOrder::NotDecided);
}

}  // namespace
}  // namespace hybridlab
