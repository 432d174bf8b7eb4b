// `hybridlab run CONFIG --dry-run`: the config checked and its runs listed (index, scene, view,
// frame, size, technique, whether the reference is cached, parameters), with how many references
// the cache already holds; nothing rendered and nothing written. (Bad configs: the runner's tests
// hold --dry-run to the same message and exit status as `run`.)
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;

TEST(RunDryRun, ListsTheQuickExperimentsRunsAndWritesNothing) {
    test::TempDir dir;
    const fs::path config = test::sourceDir() / "experiments" / "configs" / "quick.toml";
    const bool defaultOutBefore = fs::exists(fs::path("results") / "quick");
    const test::CliResult r = test::runHybridlab({"run", config.string(), "--dry-run", "--cache", (dir / "cache").string()});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const std::vector<std::string> out = test::textLines(r.out);
    ASSERT_EQ(out.size(), 2u + 160u) << r.out;
    EXPECT_CONTAINS(out[0], "experiment quick (" + config.string() + ", config hash ");
    EXPECT_CONTAINS(out[0], "): 160 runs; references: ");
    EXPECT_CONTAINS(out[0], ", 0 of them cached in " + (dir / "cache").string());
    for (const char* column : {"index", "scene", "view", "frame", "size", "technique", "reference", "parameters"}) EXPECT_CONTAINS(out[1], column);
    for (std::size_t i = 0; i < 160; ++i) {
        std::istringstream row(out[2 + i]);
        std::size_t index = 0;
        row >> index;
        EXPECT_EQ(index, i) << out[2 + i];
    }
    EXPECT_CONTAINS(out[2], "whitted-classic");
    EXPECT_CONTAINS(out[2], "320x180");
    EXPECT_CONTAINS(out[2], "max_depth=1");
    // Nothing written: no cache, no result folder (given or default).
    EXPECT_EQ(test::fileTree(dir.path()), std::vector<std::string>{});
    EXPECT_EQ(fs::exists(fs::path("results") / "quick"), defaultOutBefore);
}

TEST(RunDryRun, SaysWhichReferencesTheCacheHolds) {
    test::TempDir dir;
    const fs::path config = dir / "small.toml";
    std::ofstream(config) << "[experiment]\nrepeats = 1\nwarmup_frames = 0\n[[scenes]]\nscene = \"whitted-classic\"\n"
                             "resolutions = [[32, 18]]\n[[scenes.views]]\n[[scenes.views]]\npath = \"orbit\"\nframes = [10, 20]\nstride = 10\n"
                             "[[techniques]]\nname = \"raster\"\n";
    const std::string cache = (dir / "cache").string();
    // One run rendered: its reference (the scene camera's) is cached, the two path frames' are not.
    // (Frame 0 of the orbit is the scene camera itself, and would share its reference.)
    const test::CliResult first =
        test::runHybridlab({"run", config.string(), "--out", (dir / "out").string(), "--cache", cache, "--max-runs", "1", "--quiet"});
    ASSERT_EQ(first.exitStatus, 0) << first.err;
    const std::vector<std::string> before = test::fileTree(dir.path());
    const test::CliResult r = test::runHybridlab({"run", config.string(), "--out", (dir / "out").string(), "--cache", cache, "--dry-run"});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    const std::vector<std::string> out = test::textLines(r.out);
    ASSERT_EQ(out.size(), 2u + 3u) << r.out;
    EXPECT_CONTAINS(out[0], ": 3 runs; references: 3, 1 of them cached in " + cache);
    EXPECT_CONTAINS(out[2], " camera ");
    EXPECT_CONTAINS(out[2], " cached ");
    EXPECT_CONTAINS(out[2], "(defaults)");
    EXPECT_CONTAINS(out[3], " orbit ");
    EXPECT_CONTAINS(out[3], " to render ");
    EXPECT_CONTAINS(out[3], " 10 ");
    EXPECT_CONTAINS(out[4], " 20 ");
    EXPECT_CONTAINS(out[4], " to render ");
    EXPECT_EQ(test::fileTree(dir.path()), before) << "--dry-run wrote something";
}

}  // namespace
}  // namespace hybridlab
