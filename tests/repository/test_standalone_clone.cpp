// A clone of the repository stands on its own: cloned into a temporary folder with nothing beside
// it, the program already built (not rebuilt) renders every paper scene from the clone's scenes/
// at 64x36 with HYBRIDLAB_ASSETS unset, reading the models from the clone's scenes/assets.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/image/image_io.h"
#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;

// The scenes built from the test-scene models (README "Scenes").
std::vector<std::string> paperScenes() {
    std::vector<std::string> names = {"sponza-spheres", "sponza-armadillo", "teapot-lens", "teapot-on-floor", "dining-room"};
    for (int n = 5; n <= 30; n += 5) {
        for (const char* family : {"bunnies-falling-", "teapots-deforming-", "bunnies-falling-full-", "teapots-deforming-full-"})
            names.push_back(family + std::to_string(n));
    }
    return names;
}

// The scene files of a scenes/ folder that name a model under assets/.
std::vector<std::string> scenesUsingAssets(const fs::path& scenes) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(scenes)) {
        if (e.path().extension() != ".toml") continue;
        if (test::readTextFile(e.path()).find("\"assets/") != std::string::npos) names.push_back(e.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

TEST(StandaloneClone, RendersEveryPaperSceneWithNothingBesideIt) {
    const fs::path source = test::sourceDir();
    if (!fs::exists(source / ".git")) GTEST_SKIP() << "the source tree is not a git checkout: there is nothing to clone";
    test::TempDir dir;
    const fs::path clone = dir / "hybridlab";
    const std::string log = (dir / "git.log").string();
    const std::string command = "git clone --quiet '" + source.string() + "' '" + clone.string() + "' > '" + log + "' 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command << "\n" << test::readTextFile(log);

    // Every scene that uses a model is a paper scene, and every paper scene is in the clone.
    std::vector<std::string> expected = paperScenes();
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(scenesUsingAssets(clone / "scenes"), expected);

    const test::EnvChanges noAssets = {{"HYBRIDLAB_ASSETS", std::nullopt}};
    std::vector<test::CliRun> runs;
    for (const auto& name : expected) {
        runs.push_back({{"render", "--scene", (clone / "scenes" / (name + ".toml")).string(), "--width", "64", "--height", "36", "--out",
                         (dir / "out" / (name + ".exr")).string()},
                        noAssets});
    }
    // Two at a time: the largest scenes hold millions of triangles.
    std::vector<test::CliResult> results;
    for (std::size_t i = 0; i < runs.size(); i += 2) {
        std::vector<test::CliRun> batch(runs.begin() + i, runs.begin() + std::min(runs.size(), i + 2));
        for (auto& r : test::runHybridlabAll(batch)) results.push_back(std::move(r));
    }
    for (std::size_t i = 0; i < expected.size(); ++i) {
        SCOPED_TRACE(expected[i]);
        ASSERT_EQ(results[i].exitStatus, 0) << results[i].err;
        EXPECT_CONTAINS(results[i].out, "scene " + expected[i] + ",");
        const Image image = readImage(dir / "out" / (expected[i] + ".exr"));
        ASSERT_EQ(image.width(), 64);
        ASSERT_EQ(image.height(), 36);
        // Not one flat colour: the models are there.
        float lo = 1e30f, hi = -1e30f;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) {
                const glm::vec4 c = image.at(x, y);
                const float luminance = 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
                lo = std::min(lo, luminance);
                hi = std::max(hi, luminance);
            }
        EXPECT_GT(hi - lo, 0.05f);
    }

    // The models come from the clone's own scenes/assets: without its teapot, a teapot scene says
    // where in the clone it looked.
    fs::rename(clone / "scenes" / "assets" / "teapot", dir / "teapot-moved-away");
    const test::CliResult missing = test::runHybridlab({"scene-info", (clone / "scenes" / "teapot-lens.toml").string()}, noAssets);
    EXPECT_EQ(missing.exitStatus, 2);
    EXPECT_CONTAINS(missing.err, "not found (looked for " + (clone / "scenes" / "assets" / "teapot" / "teapot.glb").string() + ")");
}

}  // namespace
}  // namespace hybridlab
