// The `scenes` and `scene-info` commands on good input: exit status 0, the counts on stdout,
// nothing on stderr but warnings, each once; and the placed bounds of objects fitted by their bounds.
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

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

// HYBRIDLAB_SCENES naming no folder is said, not taken for a folder without scenes.
TEST(CliScenes, AScenesFolderThatIsNoneIsRefused) {
    test::TempDir dir;
    for (const std::string& scenes : {(dir / "missing").string(), test::builtinSceneFile("whitted-classic").string()}) {
        for (const std::vector<std::string>& args :
             {std::vector<std::string>{"scenes"}, std::vector<std::string>{"render", "--scene", "whitted-classic", "--out", (dir / "x.exr").string()}}) {
            const CliResult r = runHybridlab(args, {{"HYBRIDLAB_SCENES", scenes}});
            EXPECT_EQ(r.exitStatus, 2) << r.err;
            EXPECT_EQ(r.out, "");
            EXPECT_EQ(r.err, "hybridlab: error: HYBRIDLAB_SCENES=" + scenes + ": not a folder (a folder of scene files; unset it for the program's own)\n");
        }
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

// [objects.fit]: the Stanford bunny (0.15 units tall, its base at y = 0.033 as modelled) stood on
// the plane y = 0.5 at x = 1, z = 2, one unit tall; a turned cube two units across centred at
// (0, 3, 0); scene-info --json prints each object's placed bounds.
TEST(CliSceneInfo, ObjectsFittedByTheirBounds) {
    test::TempDir dir;
    const std::string bunny = (test::sourceDir() / "scenes" / "assets" / "bunny" / "bunny.glb").string();
    const std::string objects = "[materials.white]\ndiffuse = [0.8, 0.8, 0.8]\n"
                                "[[objects]]\nname = \"bunny\"\nmodel = \"" + bunny + "\"\nmaterial = \"white\"\nrotation = [0, 30, 0]\n"
                                "fit = { height = 1.0, anchor = \"bottom\", at = [1, 0.5, 2] }\n"
                                "[[objects]]\nname = \"box\"\nprimitive = \"cube\"\nmaterial = \"white\"\nrotation = [0, 45, 0]\n"
                                "scale = [1, 2, 1]\nfit = { size = 2.0, at = [0, 3, 0] }\n";
    const std::string camera = "[camera]\nposition = [0, 2, 8]\nlook_at = [0, 1, 0]\n";
    test::writeTextFile(dir / "fitted.toml", objects + camera);
    test::writeTextFile(dir / "both.toml", objects + "[[objects]]\nname = \"twice\"\nprimitive = \"cube\"\nmaterial = \"white\"\n"
                                                     "position = [1, 1, 1]\nfit = { at = [0, 0, 0] }\n" + camera);
    test::writeTextFile(dir / "flat.toml", "[materials.white]\ndiffuse = [0.8, 0.8, 0.8]\n[[objects]]\nname = \"floor\"\nprimitive = \"plane\"\n"
                                           "material = \"white\"\nfit = { height = 1.0 }\n" + camera);
    const std::vector<CliResult> r = test::runHybridlabAll({{{"scene-info", (dir / "fitted.toml").string(), "--json"}, {}},
                                                           {{"scene-info", (dir / "fitted.toml").string()}, {}},
                                                           {{"scene-info", (dir / "both.toml").string()}, {}},
                                                           {{"scene-info", (dir / "flat.toml").string()}, {}}});
    ASSERT_EQ(r[0].exitStatus, 0) << r[0].err;
    const nlohmann::json j = nlohmann::json::parse(r[0].out);
    auto bounds = [&](std::size_t object, const char* end, int axis) {
        return j.at("objects").at(object).at("bounds").at(end).at(axis).get<double>();
    };
    // The bunny: one unit tall, its bottom on y = 0.5, centred at x = 1, z = 2.
    EXPECT_NEAR(bounds(0, "max", 1) - bounds(0, "min", 1), 1.0, 1e-5);
    EXPECT_NEAR(bounds(0, "min", 1), 0.5, 1e-5);
    EXPECT_NEAR(0.5 * (bounds(0, "min", 0) + bounds(0, "max", 0)), 1.0, 1e-5);
    EXPECT_NEAR(0.5 * (bounds(0, "min", 2) + bounds(0, "max", 2)), 2.0, 1e-5);
    // The box: its largest side 2 (its height, scale's y), centred at (0, 3, 0); turned 45 degrees, its
    // x and z sides are sqrt(2) times its width of 1.
    EXPECT_NEAR(bounds(1, "max", 1) - bounds(1, "min", 1), 2.0, 1e-5);
    EXPECT_NEAR(bounds(1, "max", 0) - bounds(1, "min", 0), std::sqrt(2.0), 1e-5);
    for (int axis = 0; axis < 3; ++axis)
        EXPECT_NEAR(0.5 * (bounds(1, "min", axis) + bounds(1, "max", axis)), axis == 1 ? 3.0 : 0.0, 1e-5) << axis;
    // The text says the same.
    ASSERT_EQ(r[1].exitStatus, 0) << r[1].err;
    EXPECT_CONTAINS(r[1].out, "bounds at time 0 (min .. max)");
    EXPECT_CONTAINS(lineStartingWith(r[1].out.substr(r[1].out.find("bounds at time 0")), "box "), "(-0.7071, 2, -0.7071) .. (0.7071, 4, 0.7071)");
    // Placed twice, or fitted to a height it has not: bad input, naming the line and key.
    EXPECT_EQ(r[2].exitStatus, 2);
    EXPECT_CONTAINS(r[2].err, "both.toml:");
    EXPECT_CONTAINS(r[2].err, "the object's 'position' and fit's 'at' both place it: give one");
    EXPECT_EQ(r[3].exitStatus, 2);
    EXPECT_CONTAINS(r[3].err, "flat.toml:");
    EXPECT_CONTAINS(r[3].err, "the object's bounds have no height (a flat object): fit its 'size' instead");
}

// de Macedo & Rodrigues Tables I and II at the paper's scale: `scenes --json` gives every
// bunnies-falling-N and teapots-deforming-N a triangle count and a dynamic-triangle count within 10%
// of the table's; the full-resolution -full-N count every copy of the full model as dynamic.
TEST(CliScenes, DynamicScenesWithinTenPercentOfThePapersCounts) {
    CliResult r = runHybridlab({"scenes", "--json"}, {{"HYBRIDLAB_ASSETS", std::nullopt}});
    ASSERT_EQ(r.exitStatus, 0) << r.err;
    std::map<std::string, nlohmann::json> stats;
    for (const auto& row : nlohmann::json::parse(r.out))
        if (row.contains("stats")) stats[row.at("name").get<std::string>()] = row.at("stats");
    // N, then Table I's triangles and dynamic triangles, then Table II's (x10^3, as the paper prints them).
    const double tables[][5] = {{5, 3.2, 2.5, 3.0, 2.8},      {10, 5.7, 5.0, 5.9, 5.7},     {15, 8.2, 7.5, 8.8, 8.6},
                                {20, 10.7, 10.0, 11.6, 11.4}, {25, 13.2, 12.5, 14.5, 14.3}, {30, 15.7, 15.0, 17.4, 17.2}};
    for (const auto& row : tables) {
        const std::string n = std::to_string(static_cast<int>(row[0]));
        for (const auto& [scene, triangles, dynamic] :
             {std::tuple{"bunnies-falling-" + n, row[1], row[2]}, std::tuple{"teapots-deforming-" + n, row[3], row[4]}}) {
            SCOPED_TRACE(scene);
            ASSERT_EQ(stats.count(scene), 1u);
            EXPECT_NEAR(stats[scene].at("triangles").get<double>() / 1e3, triangles, 0.1 * triangles);
            EXPECT_NEAR(stats[scene].at("dynamic_triangles").get<double>() / 1e3, dynamic, 0.1 * dynamic);
        }
        ASSERT_EQ(stats.count("bunnies-falling-full-" + n), 1u);
        ASSERT_EQ(stats.count("teapots-deforming-full-" + n), 1u);
        EXPECT_EQ(stats["bunnies-falling-full-" + n].at("dynamic_triangles").get<double>(), row[0] * 69451);
        EXPECT_EQ(stats["teapots-deforming-full-" + n].at("dynamic_triangles").get<double>(), row[0] * 15704);
    }
    EXPECT_EQ(stats["whitted-classic"].at("dynamic_triangles"), 0);
}

}  // namespace
}  // namespace hybridlab
