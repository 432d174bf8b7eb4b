// The `scenes` and `scene-info` commands on good input: exit status 0, the counts on stdout,
// nothing on stderr but warnings, each once.
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

using test::CliResult;
using test::runHybridlab;

// The line of `text` that starts with `prefix`, or "" when none does.
std::string lineStartingWith(const std::string& text, const std::string& prefix) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.rfind(prefix, 0) == 0) return line;
    return "";
}

TEST(CliSceneInfo, SummaryOfANamedSceneAndOfAFile) {
    const std::string file = (test::fixturesDir() / "minimal.toml").string();
    auto results = test::runHybridlabAll({{{"scene-info", "whitted-classic"}, {}}, {{"scene-info", file}, {}}});
    CliResult r = results[0];
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_CONTAINS(r.out, "scene        whitted-classic\n");
    EXPECT_CONTAINS(r.out, "objects      3 (1 reflective, 1 refractive)\n");
    EXPECT_CONTAINS(r.out, "triangles    7938\n");
    EXPECT_CONTAINS(r.out, "vertices     4294\n");
    EXPECT_CONTAINS(r.out, "materials    3\n");
    EXPECT_CONTAINS(r.out, "textures     1\n");
    EXPECT_CONTAINS(r.out, "lights       2\n");
    EXPECT_CONTAINS(r.out, "camera path  orbit: 3 keys, 2 s, 61 frames at 30 fps\n");
    EXPECT_CONTAINS(r.out, "light        key (point)");
    std::string glass = lineStartingWith(r.out, "glass-sphere ");
    EXPECT_CONTAINS(glass, " 3968 ");

    // A path instead of a name.
    r = results[1];
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_CONTAINS(r.out, "scene        minimal\n");
    EXPECT_CONTAINS(r.out, "file         " + file + "\n");
    EXPECT_CONTAINS(r.out, "triangles    12\n");
}

TEST(CliScenes, ListsEverySceneAndExplainsMissingAssets) {
    test::TempDir empty;  // an assets folder without the models
    CliResult r = runHybridlab({"scenes"}, {{"HYBRIDLAB_ASSETS", empty.path().string()}});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_EQ(r.err, "");
    std::string whitted = lineStartingWith(r.out, "whitted-classic ");
    EXPECT_CONTAINS(whitted, " 7938 ");
    std::string cornell = lineStartingWith(r.out, "cornell-mirror-glass ");
    EXPECT_CONTAINS(cornell, " 3990 ");
    for (const char* scene : {"sponza-spheres ", "sponza-armadillo ", "teapot-lens "}) {
        std::string line = lineStartingWith(r.out, scene);
        EXPECT_CONTAINS(line, "unavailable: ");
        EXPECT_CONTAINS(line, "HYBRIDLAB_ASSETS=" + empty.path().string() + " does not hold it");
    }
}

// The models come with the repository (scenes/assets): no environment needed.
TEST(CliScenes, PaperScenesWithTheRepositorysAssets) {
    CliResult r = runHybridlab({"scenes"}, {{"HYBRIDLAB_ASSETS", std::nullopt}});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    // Columns: objects, vertices, triangles, lights, reflective, refractive.
    std::istringstream row(lineStartingWith(r.out, "sponza-spheres "));
    std::string name;
    std::size_t objects = 0, vertices = 0, triangles = 0, lights = 0, reflective = 0, refractive = 0;
    row >> name >> objects >> vertices >> triangles >> lights >> reflective >> refractive;
    EXPECT_EQ(name, "sponza-spheres");
    EXPECT_EQ(objects, 27u);
    EXPECT_EQ(triangles, 95148u);
    EXPECT_EQ(lights, 5u);
    EXPECT_EQ(reflective, 3u);
    EXPECT_EQ(refractive, 23u);
    EXPECT_CONTAINS(r.err, "dropped 4 degenerate triangle(s)") << "Sponza's zero-area triangles are reported";
    // Each warning once, though sponza-spheres and sponza-armadillo both load Sponza.
    std::map<std::string, int> seen;
    std::istringstream lines(r.err);
    for (std::string line; std::getline(lines, line);) ++seen[line];
    for (const auto& [line, count] : seen) EXPECT_EQ(count, 1) << line;
}

}  // namespace
}  // namespace hybridlab
