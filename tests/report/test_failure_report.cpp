// The report's "where methods fail" section (report/failures.py) on a small result set: a
// failure scene of SSR (offscreen-reflection) and a baseline path, SSR with and without its
// ray-traced fallback and raster. Its summary table must hold the worst frame, median and spike
// computed here from results.json, beside the baseline's median; its links must resolve and its
// figures have content.
#include <algorithm>
#include <fstream>
#include <map>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "experiments/runner/experiment_runner.h"
#include "tests/support/cli_runner.h"
#include "tests/support/report_checks.h"
#include "tests/support/runner_checks.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// 2 paths x 3 frames x 3 settings = 18 runs.
const char* kConfig = R"(
[experiment]
name = "failures"
warmup_frames = 0
repeats = 1
keep = []

[[scenes]]
scene = "offscreen-reflection"
resolutions = [[64, 36]]
[[scenes.views]]
path = "walk-past"
frames = [40, 80]
stride = 20

[[scenes]]
scene = "whitted-classic"
resolutions = [[64, 36]]
[[scenes.views]]
path = "orbit"
frames = [0, 40]
stride = 20

[[techniques]]
name = "ssr_fallback"
param_sets = [ { fallback = "rt" }, { fallback = "none" } ]

[[techniques]]
name = "raster"
)";

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// The summary table's row of one sequence in report.md ("" if none).
std::string tableRow(const std::string& markdown, const std::string& start) {
    const std::size_t at = markdown.find(start);
    return at == std::string::npos ? "" : markdown.substr(at, markdown.find('\n', at) - at);
}

TEST(FailureReport, SummaryTableHoldsWorstFramesMediansAndTheBaseline) {
    test::TempDir dir;
    const fs::path configFile = dir.path() / "failures.toml";
    test::writeTextFile(configFile, kConfig);
    const RunnerOptions o = test::quietRunnerOptions(dir.path() / "results", dir.path() / "cache");
    ASSERT_TRUE(runExperiment(loadExperimentConfig(configFile), o).complete);
    const fs::path report = dir.path() / "report";
    const test::CliResult r = test::runHybridlab({"report", o.outDir.string(), "--out", report.string(), "--baseline", "whitted-classic"});
    ASSERT_EQ(r.exitStatus, 0) << r.err;

    EXPECT_NE(test::readReportPage(report).find("id=\"failures\""), std::string::npos);
    EXPECT_GT(test::expectReportLinksResolve(report), 18u * 4);
    EXPECT_EQ(test::expectFiguresHaveContent(report, "failures-"), 2u * 2);  // SVG + PDF per path

    const std::vector<json> records = test::readResults(o.outDir);
    const std::string markdown = test::readTextFile(report / "report.md");
    std::map<std::string, std::vector<json>> failure, baseline;
    for (const auto& rec : records) (rec.at("scene") == "whitted-classic" ? baseline : failure)[test::reportVariant(rec)].push_back(rec);
    ASSERT_EQ(failure.size(), 3u);
    std::map<std::string, double> worstSsim;
    for (const auto& [name, rows] : failure) {
        SCOPED_TRACE(name);
        ASSERT_EQ(rows.size(), 3u);
        const std::string row = tableRow(markdown, "| offscreen-reflection | walk-past | 64x36 | " + rows[0].at("technique").get<std::string>() +
                                                       " | " + name + " | 3 | ");
        ASSERT_FALSE(row.empty()) << markdown;
        std::vector<double> ssim, ms, baseSsim;
        for (const auto& rec : rows) {
            ssim.push_back(rec.at("metrics").at("whole").at("ssim"));
            ms.push_back(rec.at("frame_ms").at("median"));
        }
        for (const auto& rec : baseline.at(name)) baseSsim.push_back(rec.at("metrics").at("whole").at("ssim"));
        const std::size_t w = std::min_element(ssim.begin(), ssim.end()) - ssim.begin();
        worstSsim[name] = ssim[w];
        // The worst frame with its number, linked to the viewer on that run.
        EXPECT_NE(row.find("[" + test::formatNumber("%.4f", ssim[w]) + " (" + std::to_string(rows[w].at("frame").get<int>()) + ")](viewer.html#run=" +
                           rows[w].at("id").get<std::string>() + ")"),
                  std::string::npos)
            << row;
        EXPECT_NE(row.find(" | " + test::formatNumber("%.4f", median(ssim)) + " | "), std::string::npos) << row;
        EXPECT_NE(row.find(" | " + test::formatNumber("%.2f", *std::max_element(ms.begin(), ms.end()) / median(ms)) + " | "), std::string::npos) << row;
        EXPECT_NE(row.find(" | " + test::formatNumber("%.4f", median(baseSsim)) + " | "), std::string::npos) << row;
    }
    // SSR alone loses the statue behind the camera; the fallback recovers it.
    EXPECT_LT(worstSsim.at("ssr_fallback [fallback=none]") + 0.3, worstSsim.at("ssr_fallback [fallback=rt]"));
    // The baseline is a column, not a row of its own.
    EXPECT_TRUE(tableRow(markdown, "| whitted-classic | orbit |").empty());
}

}  // namespace
}  // namespace hybridlab
