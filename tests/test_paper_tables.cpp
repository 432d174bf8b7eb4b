// The paper-table scripts of paper_figures/ on small result sets: Sabino 2012 Table 3
// (sabino_table3.py) must print each scene's size and the medians the records hold, and the gain
// as their ratio.
#include <cstdlib>
#include <fstream>
#include <map>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "experiments/runner/experiment_runner.h"
#include "report_checks.h"
#include "test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(PaperTables, SabinoTable3HoldsTheHybridsStagesAndTheGain) {
    test::TempDir dir;
    const fs::path config = dir.path() / "sabino.toml";
    test::writeTextFile(config, R"(
[experiment]
warmup_frames = 0
repeats = 1
keep = []
[[scenes]]
scene = "whitted-classic"
resolutions = [[48, 27]]
[[scenes]]
scene = "cornell-mirror-glass"
resolutions = [[48, 27]]
[[techniques]]
name = "heuristic_rt"
label = "hybrid"
[[techniques]]
name = "rt_only"
label = "rt"
)");
    RunnerOptions o;
    o.outDir = dir.path() / "results";
    o.cacheDir = dir.path() / "cache";
    o.quiet = true;
    ASSERT_TRUE(runExperiment(loadExperimentConfig(config), o).complete);
    const fs::path script = fs::path(HYBRIDLAB_TEST_FIXTURES).parent_path().parent_path() / "paper_figures" / "sabino_table3.py";
    const fs::path table = dir.path() / "table3.md";
    const std::string command = "/usr/bin/python3 '" + script.string() + "' '" + o.outDir.string() + "' --out '" + table.string() + "' > /dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    std::ifstream tableIn(table), resultsIn(o.outDir / "results.json");
    const std::string text((std::istreambuf_iterator<char>(tableIn)), {});
    std::map<std::string, std::map<std::string, json>> runs;  // scene -> label -> record
    for (const auto& r : json::parse(resultsIn)) runs[r.at("scene")][r.at("label")] = r;
    ASSERT_EQ(runs.size(), 2u);
    for (const auto& [scene, byLabel] : runs) {
        SCOPED_TRACE(scene);
        const json &hybrid = byLabel.at("hybrid"), &rt = byLabel.at("rt");
        const double tHybrid = hybrid.at("frame_ms").at("median"), tRt = rt.at("frame_ms").at("median");
        const std::string row = "| " + scene + " | " + std::to_string(hybrid.at("scene_stats").at("vertices").get<int>()) + " | " +
                                std::to_string(hybrid.at("scene_stats").at("triangles").get<int>()) + " | " +
                                test::formatNumber("%.1f", hybrid.at("stages").at("rast").at("median")) + " | " + test::formatNumber("%.1f", tRt) + " | " +
                                test::formatNumber("%.1f", tHybrid) + " | " + test::formatNumber("%.2f", tRt / tHybrid) + " | ";
        EXPECT_NE(text.find(row), std::string::npos) << row << "\n" << text;
        EXPECT_GT(hybrid.at("scene_stats").at("triangles").get<int>(), 0);
    }
}

}  // namespace
}  // namespace hybridlab
