// What `render` prints: the stage times and the counters that are not zero, in one aligned table,
// each counter as the frame recorded it (a hit rate of 0.23 is not printed as 0); --all-counters
// adds the zeros; --json holds every number exactly.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

// The lines between the first (the scene's) and "wrote ...": the table.
std::vector<std::string> tableLines(const std::string& out) {
    std::vector<std::string> lines;
    std::istringstream in(out);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line) && line.rfind("wrote ", 0) != 0 && line.rfind("(", 0) != 0) lines.push_back(line);
    return lines;
}

// "name   value": the value, the text after the last run of spaces.
std::string valueOf(const std::vector<std::string>& lines, const std::string& name) {
    for (const std::string& line : lines)
        if (line.rfind(name + " ", 0) == 0) return line.substr(line.find_last_of(' ') + 1);
    return "";
}

TEST(RenderOutput, CountersAsRecordedAlignedAndAsJson) {
    test::TempDir dir;
    const std::vector<std::string> render = {"render", "--scene", "whitted-classic", "--technique", "ssr_fallback", "--width", "64",
                                             "--height", "36", "--out", (dir / "frame.exr").string()};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = render;
        args.insert(args.end(), extra.begin(), extra.end());
        return test::CliRun{args, {}};
    };
    const std::vector<test::CliResult> r = test::runHybridlabAll({with({}), with({"--all-counters"}), with({"--json"})});
    for (const test::CliResult& c : r) ASSERT_EQ(c.exitStatus, 0) << c.err;
    const nlohmann::json j = nlohmann::json::parse(r[2].out);
    const nlohmann::json& counters = j.at("counters");

    // The hit rate is a fraction: printed as recorded, to six significant digits.
    const double hitRate = counters.at("ssr_hit_rate").get<double>();
    ASSERT_GT(hitRate, 0.0);
    ASSERT_LT(hitRate, 1.0);
    char expected[64];
    std::snprintf(expected, sizeof expected, "%.6g", hitRate);
    const std::vector<std::string> lines = tableLines(r[0].out);
    EXPECT_EQ(valueOf(lines, "ssr_hit_rate"), expected) << r[0].out;

    // No zero counter unless asked for, and a line saying how many were left out.
    std::size_t zeros = 0;
    for (const auto& [name, value] : counters.items()) {
        if (value.get<double>() != 0.0) continue;
        ++zeros;
        EXPECT_EQ(valueOf(lines, name), "") << name;
        EXPECT_EQ(valueOf(tableLines(r[1].out), name), "0") << name;
    }
    ASSERT_GT(zeros, 0u);
    EXPECT_CONTAINS(r[0].out, "(" + std::to_string(zeros) + " counters at 0 not shown: --all-counters)\n");
    // Every counter that is not zero, with its whole value.
    for (const auto& [name, value] : counters.items()) {
        const double v = value.get<double>();
        if (v != 0.0 && v == std::floor(v)) {
            EXPECT_EQ(valueOf(lines, name), std::to_string(static_cast<long long>(v))) << name;
        }
    }
    // Aligned: every value ends in the same column.
    for (const std::string& line : lines) EXPECT_EQ(line.size(), lines.front().size()) << line;
    EXPECT_EQ(j.at("technique"), "ssr_fallback");
    EXPECT_EQ(j.at("width"), 64);
    EXPECT_GT(j.at("frame_ms").get<double>(), 0.0);
    EXPECT_TRUE(j.at("stage_ms").contains("trace")) << j.at("stage_ms");
}

}  // namespace
}  // namespace hybridlab
