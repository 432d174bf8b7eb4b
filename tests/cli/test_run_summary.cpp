// What `hybridlab run` ends with: the runs rendered and already done, the references rendered and
// reused from the cache (each reference counted once, however many runs and groups it scores), where the
// results are, the verdict's first sentence (report/verdict.py) and the command that writes the
// report.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

// Three techniques at the scene camera and at the first frame of its orbit, which starts at the
// scene camera: six runs in two groups, one reference.
const char* kThreeRuns = R"(
[experiment]
name = "three"
warmup_frames = 0
repeats = 1
[[scenes]]
scene = "whitted-classic"
resolutions = [[32, 18]]
[[scenes.views]]
[[scenes.views]]
path = "orbit"
frames = [0, 0]
[[techniques]]
name = "raster"
[[techniques]]
name = "rt_only"
[[techniques]]
name = "ssr_fallback"
)";

TEST(RunSummary, CountsEachReferenceOnceAndEndsWithTheVerdict) {
    test::TempDir dir;
    const std::string config = (dir / "three.toml").string(), cache = (dir / "cache").string();
    test::writeTextFile(config, kThreeRuns);
    const test::CliResult first = test::runHybridlab({"run", config, "--out", (dir / "first").string(), "--cache", cache});
    ASSERT_EQ(first.exitStatus, 0) << first.err;
    EXPECT_CONTAINS(first.out, "experiment three (shard 0/1): 6 runs, 6 rendered, 0 already done; references: 1 rendered, 0 reused from the cache");
    EXPECT_CONTAINS(first.out, "results in " + (dir / "first").string() + " (results.csv, results.json)\n");
    EXPECT_CONTAINS(first.out, "verdict:\n  On whitted-classic at 32x18, ");
    EXPECT_CONTAINS(first.out, "report: `hybridlab report " + (dir / "first").string() + "` writes " +
                                   (dir / "first" / "report" / "index.html").string() + "\n");

    // The same experiment into another folder: its one reference from the cache.
    const test::CliResult again = test::runHybridlab({"run", config, "--out", (dir / "again").string(), "--cache", cache, "--quiet"});
    ASSERT_EQ(again.exitStatus, 0) << again.err;
    EXPECT_CONTAINS(again.out, "6 runs, 6 rendered, 0 already done; references: 0 rendered, 1 reused from the cache");
    EXPECT_EQ(again.out.find("verdict:"), std::string::npos) << "--quiet leaves the verdict out";
}

}  // namespace
}  // namespace hybridlab
