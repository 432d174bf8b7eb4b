// Bad input through the real program: `hybridlab scene-info FILE` must exit with status 2, print
// nothing on stdout, and print one message on stderr naming the file, the line and column, the
// key and what was wrong. The fixtures are tests/fixtures/bad/*.toml (each is fixtures/minimal.toml
// with one defect); glTF fixtures are written by the tests.
#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "common/scene/scene_catalog.h"
#include "tests/support/cli_runner.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::CliRun;
using test::EnvChanges;
using test::runHybridlab;
using test::runHybridlabAll;
using test::TempDir;

const EnvChanges kNoAssets = {{"HYBRIDLAB_ASSETS", std::nullopt}};

fs::path badFixture(const std::string& name) { return test::fixturesDir() / "bad" / name; }

// Exit status 2, empty stdout, and a one-line "hybridlab: error: ..." message holding every fragment.
void expectBadInput(const CliResult& r, const std::vector<std::string>& fragments, bool oneLine = true) {
    EXPECT_EQ(r.exitStatus, 2) << "stderr: " << r.err;
    EXPECT_EQ(r.out, "") << "bad input must not print anything on stdout";
    EXPECT_EQ(r.err.rfind("hybridlab: error: ", 0), 0u) << r.err;
    if (oneLine) {
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one message, one line: " << r.err;
    }
    for (const auto& f : fragments) EXPECT_CONTAINS(r.err, f);
}

struct BadFixture {
    const char* file;
    // "%f" stands for the fixture's path, "%d" for its folder.
    std::vector<std::string> fragments;
};

std::string expand(std::string s, const fs::path& file) {
    for (auto [token, value] : {std::pair{"%f", file.string()}, std::pair{"%d", file.parent_path().string()}}) {
        for (std::size_t at = s.find(token); at != std::string::npos; at = s.find(token, at + value.size())) s.replace(at, 2, value);
    }
    return s;
}

const BadFixture kBadFixtures[] = {
    {"syntax-error.toml", {"%f:6:1: TOML syntax error"}},
    {"unknown-top-level-key.toml", {"%f:15:2: renderer: unknown key"}},
    // The list of valid keys includes those only checked for presence (diffuse_texture, rotation).
    {"unknown-material-key.toml",
     {"%f:5:1: materials.grey.roughness: unknown key (expected one of: ", " diffuse_texture,", " specular_exponent,"}},
    {"unknown-object-key.toml", {"%f:10:1: objects[0].colour: unknown key (expected one of: ", " rotation,", " model,"}},
    {"wrong-type.toml", {"%f:5:21: materials.grey.specular_exponent: expected a number, got a string"}},
    {"out-of-range.toml", {"%f:5:11: materials.grey.opacity: expected a number in [0, 1], got 1.5"}},
    {"unknown-material-name.toml", {"%f:9:12: objects[0].material: unknown material 'gold' (defined: grey)"}},
    {"duplicate-object-name.toml", {"%f:12:8: objects[1].name: duplicate object name 'box'"}},
    {"primitive-and-model.toml", {"%f:6:1: objects[0]: expected exactly one of 'primitive' or 'model'"}},
    {"neither-primitive-nor-model.toml", {"%f:6:1: objects[0]: expected exactly one of 'primitive' or 'model'"}},
    {"unknown-primitive.toml", {"%f:8:13: objects[0].primitive: 'torus' is not one of: plane, cube, sphere, cylinder"}},
    {"missing-model.toml",
     {"%f:8:9: objects[0].model: 'models/no-such-model.glb' not found (looked for %d/models/no-such-model.glb)"}},
    {"missing-texture.toml",
     {"%f:5:19: materials.grey.diffuse_texture: 'textures/no-such-texture.png' not found (looked for "
      "%d/textures/no-such-texture.png)"}},
    {"too-many-point-lights.toml", {"%f:144:8: lights[32].type: too many point lights: at most 32 are allowed"}},
    {"one-keyframe.toml", {"%f:16:8: camera_paths.still.keys: a camera path needs at least two keyframes, got 1"}},
    {"decreasing-key-times.toml",
     {"%f:18:12: camera_paths.back.keys[1].time: keyframe times must increase (previous key is at 1.0"}},
    {"spot-without-direction.toml", {"%f:11:1: lights[0]: a spot light needs exactly one of 'direction' or 'target'"}},
    {"spot-with-direction-and-target.toml", {"%f:11:1: lights[0]: a spot light needs exactly one of 'direction' or 'target'"}},
    {"missing-camera.toml", {"%f:1:1: missing [camera] table"}},
};

// One test for all the fixtures: every test process costs ~0.3 s to start here (see
// tests/CMakeLists.txt); SCOPED_TRACE names the fixture of any failure.
TEST(CliBadInput, BadSceneFiles) {
    std::vector<CliRun> runs;
    for (const auto& fixture : kBadFixtures) {
        const fs::path file = badFixture(fixture.file);
        ASSERT_TRUE(fs::exists(file)) << file;
        runs.push_back({{"scene-info", file.string()}, kNoAssets});
    }
    const std::vector<CliResult> results = runHybridlabAll(runs);
    for (std::size_t i = 0; i < results.size(); ++i) {
        SCOPED_TRACE(kBadFixtures[i].file);
        const fs::path file = badFixture(kBadFixtures[i].file);
        std::vector<std::string> fragments;
        for (const auto& f : kBadFixtures[i].fragments) fragments.push_back(expand(f, file));
        expectBadInput(results[i], fragments);
    }
    // Every fixture on disk is in the table (asset-model.toml is tested below, with and without
    // HYBRIDLAB_ASSETS).
    std::vector<std::string> onDisk, covered = {"asset-model.toml"};
    for (const auto& e : fs::directory_iterator(test::fixturesDir() / "bad"))
        if (e.path().extension() == ".toml") onDisk.push_back(e.path().filename().string());
    for (const auto& f : kBadFixtures) covered.push_back(f.file);
    std::sort(onDisk.begin(), onDisk.end());
    std::sort(covered.begin(), covered.end());
    EXPECT_EQ(onDisk, covered);
}

TEST(CliBadInput, AssetPaths) {
    const fs::path file = badFixture("asset-model.toml");
    TempDir assets;  // set, but without the model
    // A scene beside an assets/ folder reads its models from there (as scenes/*.toml do).
    TempDir beside;
    fs::create_directories(beside / "assets");
    fs::copy_file(file, beside / "asset-model.toml");
    auto r = runHybridlabAll({{{"scene-info", file.string()}, kNoAssets},
                              {{"scene-info", file.string()}, {{"HYBRIDLAB_ASSETS", assets.path().string()}}},
                              {{"scene-info", (beside / "asset-model.toml").string()}, kNoAssets}});
    expectBadInput(r[0], {file.string() + ":8:9: objects[0].model: 'assets/no-such-folder/statue.glb' not found (looked for " +
                              (scenesDirectory() / "assets" / "no-such-folder" / "statue.glb").string() + ")",
                          "the test-scene models are in the repository's scenes/assets"});
    expectBadInput(r[1], {file.string() + ":8:9: objects[0].model: 'assets/no-such-folder/statue.glb' not found (looked for " +
                              (assets.path() / "no-such-folder" / "statue.glb").string() + ")",
                          "HYBRIDLAB_ASSETS=" + assets.path().string() + " does not hold it"});
    expectBadInput(r[2], {"objects[0].model: 'assets/no-such-folder/statue.glb' not found (looked for " +
                          (beside / "assets" / "no-such-folder" / "statue.glb").string() + ")"});
}

// A scene laid out like fixtures/minimal.toml whose one object is the model `model` (line 8,
// column 9 holds the path).
void writeSceneWithModel(const fs::path& scene, const std::string& model) {
    test::writeTextFile(scene, "# A scene whose object is a model written by the test.\n"
                               "\n"
                               "[materials.grey]\n"
                               "diffuse = [0.5, 0.5, 0.5]\n"
                               "\n"
                               "[[objects]]\n"
                               "name = \"model\"\n"
                               "model = \"" + model + "\"\n"
                               "material = \"grey\"\n"
                               "\n"
                               "[camera]\n"
                               "position = [0.0, 1.0, 5.0]\n"
                               "look_at = [0.0, 0.0, 0.0]\n");
}

TEST(CliBadInput, BadGltfModels) {
    TempDir dir;
    // An index past the last vertex.
    test::GltfBuilder b;
    int pos = b.addFloats(test::kTrianglePositions, "VEC3");
    b.setRoots({b.addNode({{"mesh", b.addMesh("broken", pos, -1, b.addIndices({0, 1, 7}))}})});
    b.writeGltf(dir / "broken.gltf");
    writeSceneWithModel(dir / "index.toml", "broken.gltf");
    // A NaN in the vertex data of a .glb.
    std::vector<float> positions = test::kTrianglePositions;
    positions[6] = std::numeric_limits<float>::quiet_NaN();  // vertex 2, x
    test::GltfBuilder nan;
    nan.setRoots({nan.addNode({{"mesh", nan.addMesh("nan", nan.addFloats(positions, "VEC3"))}})});
    nan.writeGlb(dir / "nan.glb");
    writeSceneWithModel(dir / "nan.toml", "nan.glb");
    // JSON that ends early.
    test::writeTextFile(dir / "truncated.gltf", "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"meshes\": [\n");
    writeSceneWithModel(dir / "json.toml", "truncated.gltf");

    auto r = runHybridlabAll({{{"scene-info", (dir / "index.toml").string()}, kNoAssets},
                              {{"scene-info", (dir / "nan.toml").string()}, kNoAssets},
                              {{"scene-info", (dir / "json.toml").string()}, kNoAssets}});
    expectBadInput(r[0], {(dir / "index.toml").string() + ":8:9: objects[0].model: " + (dir / "broken.gltf").string() +
                          ": mesh 'broken' primitive 0: index 7 at position 2 is out of range (the primitive has 3 vertices)"});
    expectBadInput(r[1], {(dir / "nan.toml").string() + ":8:9: objects[0].model: " + (dir / "nan.glb").string() +
                          ": mesh 'nan' primitive 0 POSITION: element 2 is not finite (NaN or infinity)"});
    // tinygltf's reason may span lines: joined into one.
    expectBadInput(r[2], {(dir / "json.toml").string() + ":8:9: objects[0].model: " + (dir / "truncated.gltf").string() +
                          ": not a valid glTF 2.0 file ("});
}

TEST(CliBadInput, UnknownSceneNameOrFile) {
    TempDir dir;
    const std::string missing = (dir / "nowhere.toml").string();
    auto r = runHybridlabAll({{{"scene-info", "no-such-scene"}, {}}, {{"scene-info", missing}, {}}});
    expectBadInput(r[0], {"unknown scene 'no-such-scene' (built-in scenes: bunnies-falling-10, ", " cornell-mirror-glass, ", " whitted-classic",
                          "; or give a path to a .toml file)"});
    expectBadInput(r[1], {missing + ": scene file not found"});
}

TEST(CliBadInput, BadArguments) {
    // An unknown option, a missing argument, an unknown command.
    auto r = runHybridlabAll({{{"scene-info", "whitted-classic", "--frobnicate"}, {}},
                              {{"scene-info"}, {}},
                              {{"render-everything"}, {}}});
    expectBadInput(r[0], {"--frobnicate", "(hybridlab --help for usage)"});
    expectBadInput(r[1], {"scene is required", "(hybridlab --help for usage)"});
    expectBadInput(r[2], {"unknown command 'render-everything'", "commands: scenes, scene-info, render", "hybridlab --help for usage"});
}

TEST(CliWarnings, DegenerateTriangleIsOneWarningLine) {
    TempDir dir;
    test::GltfBuilder b;
    // A quad and one triangle with a repeated index.
    int pos = b.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    int idx = b.addIndices({0, 1, 2, 0, 2, 3, 1, 1, 2});
    b.setRoots({b.addNode({{"mesh", b.addMesh("chipped", pos, -1, idx)}})});
    b.writeGltf(dir / "chipped.gltf");
    writeSceneWithModel(dir / "scene.toml", "chipped.gltf");
    CliResult r = runHybridlab({"scene-info", (dir / "scene.toml").string()}, kNoAssets);
    EXPECT_EQ(r.exitStatus, 0) << r.err;
    EXPECT_EQ(r.err, "warning: " + (dir / "chipped.gltf").string() + ": mesh 'chipped' primitive 0: dropped 1 degenerate triangle(s)\n");
    EXPECT_CONTAINS(r.out, "triangles    2\n");
    EXPECT_CONTAINS(r.out, "\nmodel                             2 ");
}

}  // namespace
}  // namespace hybridlab
