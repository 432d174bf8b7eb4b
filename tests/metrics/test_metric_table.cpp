// The metric table (metrics/metric_table.h) is the one declaration of the metrics: the report reads
// the same table for old result sets, and a metric added in one place (AddedMetricScope) reaches
// the record, the report's tables and the viewer's read-out without any reader naming it.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "experiments/runner/experiment_runner.h"
#include "metrics/metric_table.h"
#include "tests/support/cli_runner.h"
#include "tests/support/runner_checks.h"
#include "tests/support/shell_command.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(MetricTable, TheReportReadsTheSameTable) {
    const test::CommandOutput py = test::commandOutput("cd '" + (test::sourceDir() / "report").string() +
                                                       "' && /usr/bin/python3 -c 'import json, results; print(json.dumps(results.BUILT_IN_METRICS))'");
    ASSERT_EQ(py.exitStatus, 0);
    EXPECT_EQ(json::parse(py.out), metricTableJson());
}

TEST(MetricTable, KeysAreUniqueAndRangesOrdered) {
    for (std::size_t i = 0; i < std::size(kMetricTable); ++i) {
        EXPECT_LT(kMetricTable[i].low, kMetricTable[i].high) << kMetricTable[i].key;
        for (std::size_t j = 0; j < i; ++j) EXPECT_STRNE(kMetricTable[i].key, kMetricTable[j].key);
    }
}

const char* kConfig = R"(
[experiment]
name = "added-metric"
warmup_frames = 0
repeats = 1
keep = []

[[scenes]]
scene = "cornell-mirror-glass"
resolutions = [[48, 32]]

[[techniques]]
name = "rt_only"
)";

// A score that exists only here: 0.25 on the whole image, 0.75 on the reflective and refractive pixels.
AddedMetric throwawayMetric() {
    return {{"throwaway", "Throwaway score", Better::Higher, 0.0, 1.0, "", "", false, true, 4, 0.0},
            [](const cv::Mat3f&, const cv::Mat3f&, const cv::Mat1b* region) { return region ? 0.75 : 0.25; }};
}

TEST(MetricTable, AMetricAddedInOnePlaceReachesTheRecordTheReportAndTheViewer) {
    const AddedMetricScope added(throwawayMetric());
    test::TempDir dir;
    const fs::path config = dir.path() / "added-metric.toml";
    test::writeTextFile(config, kConfig);
    const fs::path results = dir.path() / "results";
    ASSERT_TRUE(runExperiment(loadExperimentConfig(config), test::quietRunnerOptions(results, dir.path() / "cache")).complete);

    // The record holds its value on each region, and the result set its row of the table.
    const std::vector<json> records = test::readResults(results);
    ASSERT_EQ(records.size(), 1u);
    EXPECT_EQ(records[0].at("metrics").at("whole").at("throwaway"), 0.25);
    EXPECT_EQ(records[0].at("metrics").at("masked").at("throwaway"), 0.75);
    const json experiment = json::parse(test::readTextFile(results / "experiment.json"));
    EXPECT_EQ(experiment.at("metric_table").back().at("label"), "Throwaway score");

    // The report's tables: the summary's column on both regions, and each run's row.
    const fs::path report = dir.path() / "report";
    const test::CliResult r = test::runHybridlab({"report", results.string(), "--out", report.string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    const std::string markdown = test::readTextFile(report / "report.md");
    EXPECT_CONTAINS(markdown, " | Throwaway score | ");
    EXPECT_CONTAINS(markdown, " | Throwaway score refl./refr. |");
    EXPECT_CONTAINS(markdown, " | 0.2500 | ");
    EXPECT_CONTAINS(markdown, " | 0.7500 |");
    EXPECT_CONTAINS(test::readTextFile(report / "index.html"), "<th>Throwaway score</th>");

    // The viewer's read-out under the run's image, through the report's copy of its modules, under
    // Debian's Node.js (setup.sh's nodejs), not whichever node the PATH finds first.
    const test::CommandOutput viewer = test::commandOutput("/usr/bin/node '" + (test::sourceDir() / "tests/report/viewer/read_out_runs.mjs").string() +
                                                           "' '" + report.string() + "'");
    ASSERT_EQ(viewer.exitStatus, 0) << viewer.out;
    EXPECT_CONTAINS(viewer.out, " · Throwaway score 0.2500");
    EXPECT_CONTAINS(viewer.out, "refl./refr.: ");
    EXPECT_CONTAINS(viewer.out, " · Throwaway score 0.7500");
}

}  // namespace
}  // namespace hybridlab
