// A result set written before the current record format (experiments/results.migrations.json)
// still reports: the runner's set made old here (no schema_version, version 1's stage and counter
// names, no metric table, no HDR-FLIP) is read under the current names by the report
// (report/results.py) and by the viewer (report/viewer/result_set.js), which agree on the migration.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "experiments/runner/experiment_runner.h"
#include "experiments/runner/run_record.h"
#include "tests/support/cli_runner.h"
#include "tests/support/runner_checks.h"
#include "tests/support/shell_command.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* kConfig = R"(
[experiment]
name = "old-set"
warmup_frames = 0
repeats = 1
keep = []

[[scenes]]
scene = "whitted-classic"
resolutions = [[48, 32]]

[[techniques]]
name = "rt_only"

[[techniques]]
name = "whitted"
label = "depth2"
params = { max_depth = 2 }
)";

// What `code` prints, run by report/results.py's Python with `results` imported.
std::string resultsPy(const std::string& code) {
    const test::CommandOutput out = test::commandOutput("cd '" + (test::sourceDir() / "report").string() +
                                                        "' && /usr/bin/python3 -c 'import json, results; " + code + "'");
    EXPECT_EQ(out.exitStatus, 0) << code;
    return out.out;
}

TEST(OldResultSets, TheRunnersVersionIsTheMigrationsLast) {
    EXPECT_EQ(resultsPy("print(results.SCHEMA_VERSION)"), std::to_string(kResultsSchemaVersion) + "\n");
}

TEST(OldResultSets, AVersionOneSetReportsUnderTheCurrentNames) {
    test::TempDir dir;
    const fs::path config = dir.path() / "old-set.toml";
    test::writeTextFile(config, kConfig);
    const fs::path results = dir.path() / "results";
    ASSERT_TRUE(runExperiment(loadExperimentConfig(config), test::quietRunnerOptions(results, dir.path() / "cache")).complete);
    std::vector<json> records = test::readResults(results);
    ASSERT_EQ(records.size(), 2u);
    // Made old: version 1's names, and what version 1 sets lacked.
    for (json& r : records) {
        EXPECT_EQ(r.at("schema_version"), kResultsSchemaVersion);
        r.erase("schema_version");
        ASSERT_TRUE(r.at("stages").contains("trace"));
        r["stages"]["rayt"] = r["stages"]["trace"];
        r["stages"].erase("trace");
        r["counters"]["vk_gbuffer_upload_input_primitives"] = 7.0;
        for (const char* region : {"whole", "masked"})
            if (r["metrics"][region].is_object()) r["metrics"][region].erase("flip_hdr");
    }
    test::writeTextFile(results / "results.json", json(records).dump(1));
    json experiment = json::parse(test::readTextFile(results / "experiment.json"));
    experiment.erase("metric_table");
    test::writeTextFile(results / "experiment.json", experiment.dump(1));

    // The records are valid (migrated as results.py loads them), and the report is written: its
    // summary from the built-in metric table, a dash where the set predates a metric.
    EXPECT_EQ(test::commandOutput("/usr/bin/python3 '" + (test::sourceDir() / "report" / "results.py").string() + "' '" +
                                  results.string() + "'").exitStatus, 0);
    const fs::path report = dir.path() / "report";
    const test::CliResult r = test::runHybridlab({"report", results.string(), "--out", report.string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    const std::string markdown = test::readTextFile(report / "report.md");
    EXPECT_CONTAINS(markdown, "| SSIM | FLIP (LDR) | HDR-FLIP |");
    EXPECT_CONTAINS(markdown, " | - |");

    // The report and the viewer read the old names as the current ones, alike.
    const std::string loaded = resultsPy("print(json.dumps([(r[\"id\"], sorted(r[\"stages\"]), r[\"counters\"].get(\"vk_gbuffer.upload_input_primitives\")) "
                                         "for r in results.load(\"" + results.string() + "\")]))");
    for (const json& run : json::parse(loaded)) {
        EXPECT_NE(std::find(run[1].begin(), run[1].end(), "trace"), run[1].end()) << run;
        EXPECT_EQ(std::find(run[1].begin(), run[1].end(), "rayt"), run[1].end()) << run;
        EXPECT_EQ(run[2], 7.0);
    }
    const test::CommandOutput viewer = test::commandOutput("/usr/bin/node '" + (test::sourceDir() / "tests/report/viewer/read_out_runs.mjs").string() +
                                                           "' '" + report.string() + "'");
    ASSERT_EQ(viewer.exitStatus, 0) << viewer.out;
    for (const json& record : records) {
        const std::string id = record.at("id");
        const std::size_t at = viewer.out.find(id + ": stages ");
        ASSERT_NE(at, std::string::npos) << viewer.out;
        const std::string line = viewer.out.substr(at, viewer.out.find('\n', at) - at);
        EXPECT_CONTAINS(line, "trace");
        EXPECT_EQ(line.find("rayt"), std::string::npos) << line;
        EXPECT_CONTAINS(line, "HDR-FLIP -");
    }
}

}  // namespace
}  // namespace hybridlab
