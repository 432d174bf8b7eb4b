// `hybridlab run --shard i/n`: the runs split by estimated cost (shard_partition.h), not by index
// modulo n. No rendering: the partition of a config that mixes 320x180 and 1280x720 runs.
#include <algorithm>
#include <numeric>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/runner/experiment_config.h"
#include "experiments/runner/shard_partition.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;

// Two scenes at both sizes, their camera and three path frames, four techniques: 64 runs, half
// of them 1280x720 (16 times the pixels), eight sharing each reference.
constexpr const char* kMixedSizes = R"(
[experiment]
name = "mixed"
[[scenes]]
scene = "whitted-classic"
resolutions = [[320, 180], [1280, 720]]
[[scenes.views]]
[[scenes.views]]
path = "orbit"
frames = [0, 40]
stride = 20
[[scenes]]
scene = "cornell-mirror-glass"
resolutions = [[1280, 720], [320, 180]]
[[scenes.views]]
[[scenes.views]]
path = "dolly"
frames = [0, 30]
stride = 15
[[techniques]]
name = "raster"
[[techniques]]
name = "rt_only"
[[techniques]]
name = "heuristic_rt"
[[techniques]]
name = "ssr_fallback"
)";

ExperimentConfig loadConfig(const test::TempDir& dir, const char* text) {
    const fs::path file = dir / "config.toml";
    test::writeTextFile(file, text);
    return loadExperimentConfig(file);
}

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()); }
double largest(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

// A shard's cost as the partition counts it: its runs, and each reference they need once.
double shardCost(const ExperimentConfig& config, const std::vector<const RunSpec*>& runs) {
    double cost = 0.0;
    std::set<std::tuple<std::size_t, std::string, int, int, int>> references;
    for (const RunSpec* r : runs) {
        cost += estimatedRunCost(config, *r);
        if (references.insert({r->scene, r->cameraPath, r->frame, r->width, r->height}).second) cost += estimatedReferenceCost(config, *r);
    }
    return cost;
}

TEST(ShardPartition, BalancesMixedSizesWithin25PercentOfTheMean) {
    test::TempDir dir;
    const ExperimentConfig config = loadConfig(dir, kMixedSizes);
    const std::vector<RunSpec> runs = planRuns(config);
    ASSERT_EQ(runs.size(), 64u);
    // A 1280x720 run costs 16 times the same run at 320x180, and a technique's class scales it.
    EXPECT_DOUBLE_EQ(estimatedRunCost(config, runs[16]) / estimatedRunCost(config, runs[0]), 16.0);
    EXPECT_GT(estimatedRunCost(config, runs[1]), estimatedRunCost(config, runs[0]));  // rt_only over raster

    for (int n = 1; n <= 7; ++n) {
        SCOPED_TRACE("n = " + std::to_string(n));
        const ShardPartition p = partitionRuns(config, runs, n);
        ASSERT_EQ(p.estimatedCost.size(), static_cast<std::size_t>(n));
        // Every run in exactly one shard; each shard's recorded cost is its runs' and references'.
        std::vector<int> seen(runs.size(), 0);
        for (int s = 0; s < n; ++s) {
            const auto mine = p.runsOf(runs, s);
            EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end(), [](const RunSpec* a, const RunSpec* b) { return a->index < b->index; }));
            for (const RunSpec* r : mine) ++seen[r->index];
            EXPECT_NEAR(p.estimatedCost[s], shardCost(config, mine), 1e-9 * p.estimatedCost[s]);
        }
        EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(runs.size()));
        EXPECT_LE(largest(p.estimatedCost), 1.25 * mean(p.estimatedCost)) << "largest " << largest(p.estimatedCost) << ", mean " << mean(p.estimatedCost);
        // Deterministic: every shard computes the same partition.
        EXPECT_EQ(partitionRuns(config, runs, n).shardOfRun, p.shardOfRun);
    }
    // With one shard, the estimate counts each of the 16 references once.
    double runsOnly = 0.0, referencesOnly = 0.0;
    std::set<std::tuple<std::size_t, std::string, int, int, int>> references;
    for (const RunSpec& r : runs) {
        runsOnly += estimatedRunCost(config, r);
        if (references.insert({r.scene, r.cameraPath, r.frame, r.width, r.height}).second) referencesOnly += estimatedReferenceCost(config, r);
    }
    EXPECT_EQ(references.size(), 16u);
    EXPECT_DOUBLE_EQ(partitionRuns(config, runs, 1).estimatedCost[0], runsOnly + referencesOnly);
}

// The case index modulo n gets wrong: each scene's two sizes in a row with one run each, so shard
// 1 of 2 would take every 1280x720 run.
TEST(ShardPartition, SplitsWhatIndexModuloGivesOneShard) {
    test::TempDir dir;
    const ExperimentConfig config = loadConfig(dir, R"(
[[scenes]]
scene = "whitted-classic"
resolutions = [[320, 180], [1280, 720]]
[[scenes]]
scene = "cornell-mirror-glass"
resolutions = [[320, 180], [1280, 720]]
[[techniques]]
name = "heuristic_rt"
)");
    const std::vector<RunSpec> runs = planRuns(config);
    ASSERT_EQ(runs.size(), 4u);
    std::vector<double> modulo(2, 0.0);
    for (const RunSpec& r : runs) modulo[r.index % 2] += estimatedRunCost(config, r) + estimatedReferenceCost(config, r);
    EXPECT_GT(largest(modulo), 1.8 * mean(modulo));  // what the test below would catch

    const ShardPartition p = partitionRuns(config, runs, 2);
    EXPECT_NE(p.shardOfRun[1], p.shardOfRun[3]);  // one 1280x720 run each
    EXPECT_LE(largest(p.estimatedCost), 1.25 * mean(p.estimatedCost));
}

// Runs that share a reference stay on one shard where the balance allows: two equal references
// with four runs each over two shards go one reference a shard, each rendered once.
TEST(ShardPartition, KeepsRunsOfOneReferenceTogether) {
    test::TempDir dir;
    const ExperimentConfig config = loadConfig(dir, R"(
[[scenes]]
scene = "whitted-classic"
resolutions = [[320, 180]]
[[scenes.views]]
path = "orbit"
frames = [0, 10]
stride = 10
[[techniques]]
name = "raster"
[[techniques]]
name = "rt_only"
[[techniques]]
name = "heuristic_rt"
[[techniques]]
name = "ssr_fallback"
)");
    const std::vector<RunSpec> runs = planRuns(config);
    ASSERT_EQ(runs.size(), 8u);
    const ShardPartition p = partitionRuns(config, runs, 2);
    for (const RunSpec& r : runs) EXPECT_EQ(p.shardOfRun[r.index], p.shardOfRun[r.frame == 0 ? 0 : 4]) << r.id;
    EXPECT_NE(p.shardOfRun[0], p.shardOfRun[4]);
}

}  // namespace
}  // namespace hybridlab
