// Bad input through the real program, one case a line: the arguments, the exit status (2: bad
// input, 3: a file that cannot be written), a fragment of the one-line message (with the
// file:line:column where there is a file), and nothing written: each case's output path (%o)
// must not exist afterwards. The inputs are written by the test into one folder (%d). The scene
// files fixtures/bad/*.toml and the glTF cases of test_cli_bad_input.cpp are the other half of
// the table.
#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::CliRun;
using test::TempDir;

// A scene laid out like fixtures/minimal.toml with `objectLines` in its one object (from line 8)
// and `materialLines` in its material (from line 5).
std::string sceneText(const std::string& materialLines, const std::string& objectLines) {
    return "# A scene written by the test.\n"    // 1
           "\n"                                  // 2
           "[materials.grey]\n"                  // 3
           "diffuse = [0.5, 0.5, 0.5]\n" +       // 4
           materialLines +                        // 5
           "\n"
           "[[objects]]\n"
           "name = \"thing\"\n" +
           objectLines +
           "material = \"grey\"\n"
           "\n"
           "[camera]\n"
           "position = [0.0, 1.0, 5.0]\n"
           "look_at = [0.0, 0.0, 0.0]\n";
}

// An experiment config: one scene with `sceneLines` (from line 2), one technique.
std::string configText(const std::string& sceneLines) {
    return "[[scenes]]\n" + sceneLines + "\n[[techniques]]\nname = \"whitted\"\n";
}

// Writes every input the cases name into `d`.
void writeInputs(const fs::path& d) {
    using test::writeTextFile;
    fs::create_directories(d);
    // Objects: tessellation beyond the bounds, a model that is a folder, a glTF accessor whose
    // count (2^60) would allocate exabytes.
    writeTextFile(d / "slices.toml", sceneText("", "primitive = \"sphere\"\nslices = 300000\n"));
    writeTextFile(d / "sphere-product.toml", sceneText("", "primitive = \"sphere\"\nslices = 4096\nstacks = 4096\n"));
    fs::create_directories(d / "folder.glb");
    writeTextFile(d / "model-folder.toml", sceneText("", "model = \"folder.glb\"\n"));
    test::GltfBuilder b;
    const int pos = b.addFloats(test::kTrianglePositions, "VEC3");
    b.document()["accessors"][pos]["count"] = 1ULL << 60;
    b.setRoots({b.addNode({{"mesh", b.addMesh("huge", pos)}})});
    b.writeGltf(d / "huge.gltf");
    writeTextFile(d / "huge-count.toml", sceneText("", "model = \"huge.gltf\"\n"));
    // A glTF whose buffer `uri` is a folder (tinygltf read it as a file of 2^63 - 1 bytes).
    test::GltfBuilder quad;
    quad.setRoots({quad.addNode({{"mesh", quad.addMesh("quad", quad.addFloats(test::kTrianglePositions, "VEC3"))}})});
    nlohmann::json bufferFolder = nlohmann::json::parse(quad.gltfText());
    bufferFolder["buffers"][0]["uri"] = ".";
    writeTextFile(d / "buffer-folder.gltf", bufferFolder.dump());
    writeTextFile(d / "buffer-folder.toml", sceneText("", "model = \"buffer-folder.gltf\"\n"));
    // Textures that are not images: text, and a folder. scene-info does not decode textures, but
    // checks them.
    writeTextFile(d / "not-an-image.png", "this is text, not a PNG\n");
    writeTextFile(d / "texture-text.toml", sceneText("diffuse_texture = \"not-an-image.png\"\n", "primitive = \"cube\"\n"));
    fs::create_directories(d / "folder.png");
    writeTextFile(d / "texture-folder.toml", sceneText("diffuse_texture = \"folder.png\"\n", "primitive = \"cube\"\n"));
    // A texture that is a device which never ends (a reader would read it forever).
    writeTextFile(d / "texture-device.toml", sceneText("diffuse_texture = \"/dev/zero\"\n", "primitive = \"cube\"\n"));
    // A camera path of 2e10 frames (frame numbers are ints).
    writeTextFile(d / "long-path.toml", sceneText("", "primitive = \"cube\"\n") +
                                            "\n[camera_paths.long]\nfps = 10000.0\nkeys = [\n"
                                            "  { time = 0.0, position = [0.0, 1.0, 5.0], look_at = [0.0, 0.0, 0.0] },\n"
                                            "  { time = 1000000.0, position = [1.0, 1.0, 5.0], look_at = [0.0, 0.0, 0.0] },\n]\n");
    // Configs: a resolution and a frame of 2^32 + something, which an int would wrap.
    writeTextFile(d / "wrap-resolution.toml", configText("scene = \"whitted-classic\"\nresolutions = [[4294967360, 64]]\n"));
    writeTextFile(d / "wrap-frame.toml",
                  configText("scene = \"whitted-classic\"\nresolutions = [[32, 32]]\n[[scenes.views]]\npath = \"orbit\"\nframes = [0, 4294967296]\n"));
    fs::create_directories(d / "a-folder");
    writeTextFile(d / "ok.toml", configText("scene = \"whitted-classic\"\nresolutions = [[32, 32]]\n"));
    // Shard folders as `run --shard i/2` starts them (no runs recorded yet): two of experiment 'a',
    // one of another config.
    const auto shard = [&](const std::string& folder, const std::string& name, char hash, int index) {
        fs::create_directories(d / folder);
        writeTextFile(d / folder / "experiment.json",
                      "{\"name\": \"" + name + "\", \"config_hash\": \"" + std::string(64, hash) + "\", \"runs_total\": 2, \"shard\": " +
                          "{\"index\": " + std::to_string(index) + ", \"count\": 2, \"partition\": \"estimated-cost\", \"runs\": 1}}\n");
    };
    shard("shard-a0", "a", 'a', 0);
    shard("shard-a1", "a", 'a', 1);
    shard("shard-b1", "b", 'b', 1);
}

struct BadInputCase {
    std::vector<std::string> args;  // "%d": the inputs' folder; "%o": this case's output path
    int exitStatus;
    std::string message;            // a fragment of the message, "%d" expanded
};

const std::vector<std::string> kRender = {"render", "--scene", "whitted-classic", "--width", "32", "--height", "24"};

std::vector<std::string> render(std::vector<std::string> extra) {
    std::vector<std::string> a = kRender;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

const std::vector<BadInputCase> kCases = {
    // Numbers on the command line: finite, in range, within their type.
    {render({"--time", "nan", "--out", "%o/x.exr"}), 2, "--time: expected a finite number in [-1e+06, 1e+06], got nan"},
    {render({"--time", "inf", "--out", "%o/x.exr"}), 2, "--time: expected a finite number in [-1e+06, 1e+06], got inf"},
    {render({"--time", "1e300", "--out", "%o/x.exr"}), 2, "--time: expected a number in [-1e+06, 1e+06], got 1e+300"},
    {render({"--camera-path", "orbit", "--frame", "4294967296", "--out", "%o/x.exr"}), 2, "--frame: expected an integer in [0, 10000000], got 4294967296"},
    {{"render", "--scene", "whitted-classic", "--width", "4294967328", "--height", "24", "--out", "%o/x.exr"}, 2,
     "--width: expected an integer in [1, 16384], got 4294967328"},
    {render({"--camera-path", "orbit", "--frame", "61", "--out", "%o/x.exr"}), 2, "frame 61 is outside camera path 'orbit' (frames 0 to 60)"},
    // Output paths.
    {render({"--out", "%d/folder.png"}), 2, "--out %d/folder.png: %d/folder.png is a directory, expected an image file name"},
    {render({"--out", "/proc/hybridlab-no-such-folder/x.exr"}), 3, "/proc/hybridlab-no-such-folder: cannot create folder ("},
    // Scene files.
    {{"scene-info", "%d/slices.toml"}, 2, "%d/slices.toml:9:10: objects[0].slices: expected an integer in [3, 4096], got 300000"},
    {{"scene-info", "%d/sphere-product.toml"}, 2,
     "%d/sphere-product.toml:10:10: objects[0].stacks: slices 4096 x stacks 4096 make 16785409 vertices, more than the limit of 4000000"},
    {{"scene-info", "%d/model-folder.toml"}, 2, "%d/model-folder.toml:8:9: objects[0].model: 'folder.glb' is a directory (%d/folder.glb), expected a file"},
    {{"scene-info", "%d/huge-count.toml"}, 2,
     "%d/huge-count.toml:8:9: objects[0].model: %d/huge.gltf: mesh 'huge' primitive 0 POSITION: accessor's 1152921504606846976 elements of 12 bytes"},
    {{"scene-info", "%d/buffer-folder.toml"}, 2, "%d/buffer-folder.toml:8:9: objects[0].model: %d/buffer-folder.gltf: not a valid glTF 2.0 file ("},
    {{"scene-info", "%d/texture-text.toml"}, 2,
     "%d/texture-text.toml:5:19: materials.grey.diffuse_texture: %d/not-an-image.png: cannot read image ("},
    {{"scene-info", "%d/texture-folder.toml"}, 2,
     "%d/texture-folder.toml:5:19: materials.grey.diffuse_texture: 'folder.png' is a directory (%d/folder.png), expected a file"},
    {{"scene-info", "%d/texture-device.toml"}, 2,
     "%d/texture-device.toml:5:19: materials.grey.diffuse_texture: /dev/zero: is not a regular file (a device or a pipe), expected an image file"},
    {{"scene-info", "%d/long-path.toml"}, 2, "%d/long-path.toml:16:7: camera_paths.long.fps: the path's 1e+06 s at 10000 fps make more frames than the limit of 10000000"},
    {{"scene-info", "%d/a-folder"}, 2, "%d/a-folder: is a directory, expected a scene file (.toml) or a scene's name"},
    // Experiment configs.
    {{"run", "%d/a-folder", "--out", "%o"}, 2, "%d/a-folder: is a directory, expected a TOML file"},
    {{"run", "%d/wrap-resolution.toml", "--out", "%o"}, 2,
     "%d/wrap-resolution.toml:3:15: scenes[0].resolutions: expected an integer in [11, 16384], got 4294967360"},
    {{"run", "%d/wrap-frame.toml", "--out", "%o"}, 2,
     "%d/wrap-frame.toml:6:10: scenes[0].views[0].frames: expected 0 <= first <= last <= 60 (path 'orbit' has 61 frames), got [0, 4294967296]"},
    // Shards: i/n with 0 <= i < n, nothing else; merging shards of two configs, a missing or an
    // unfinished shard.
    {{"run", "%d/ok.toml", "--out", "%o", "--shard", "3/3"}, 2, "--shard 3/3: expected i/n, whole numbers with 0 <= i < n <= 100000"},
    {{"run", "%d/ok.toml", "--out", "%o", "--shard", "0/0"}, 2, "--shard 0/0: expected i/n, whole numbers with 0 <= i < n <= 100000"},
    {{"run", "%d/ok.toml", "--out", "%o", "--shard", "a/b"}, 2, "--shard a/b: expected i/n"},
    {{"run", "%d/ok.toml", "--out", "%o", "--shard", "1/2/3"}, 2, "--shard 1/2/3: expected i/n"},
    {{"run", "%d/ok.toml", "--out", "%o", "--shard=-1/2"}, 2, "--shard -1/2: expected i/n"},
    {{"run", "%d/ok.toml", "--out", "%o", "--shard", "4294967297/4294967298"}, 2, "--shard 4294967297/4294967298: expected i/n"},
    {{"run", "%d/ok.toml", "--dry-run", "--shard", "2/1"}, 2, "--shard 2/1: expected i/n"},
    {{"merge", "--out", "%o", "%d/shard-a0", "%d/shard-b1"}, 2,
     "merge: %d/shard-b1 is shard 1/2 of experiment 'b' (config hash bbbbbbbbbbbb, runs split by estimated-cost), not of %d/shard-a0's "
     "experiment 'a'"},
    {{"merge", "--out", "%o", "%d/shard-a1"}, 2, "merge: shard 0/2 of experiment 'a' is missing"},
    {{"merge", "--out", "%o", "%d/shard-a0", "%d/shard-a0"}, 2, "merge: %d/shard-a0 and %d/shard-a0 are both shard 0/2"},
    {{"merge", "--out", "%o", "%d/shard-a0", "%d/shard-a1"}, 2, "merge: %d/shard-a0 (shard 0/2) holds 0 of its 1 runs"},
    {{"merge", "--out", "%o", "%d/shard-a0", "%d/a-folder"}, 2, "%d/a-folder: not an experiment folder (no experiment.json)"},
    // Arguments: one line, with the pointer to --help on it.
    {{"scene-info", "whitted-classic", "--frobnicate"}, 2, "The following argument was not expected: --frobnicate (hybridlab --help for usage)"},
    {{"frobnicate"}, 2, "unknown command 'frobnicate' (commands: "},
};

std::string expand(std::string s, const fs::path& d, const fs::path& o) {
    for (auto [token, value] : {std::pair{"%d", d.string()}, std::pair{"%o", o.string()}}) {
        for (std::size_t at = s.find(token); at != std::string::npos; at = s.find(token, at + value.size())) s.replace(at, 2, value);
    }
    return s;
}

TEST(BadInputTable, OneMessageExitStatusAndNothingWritten) {
    TempDir dir;
    const fs::path inputs = dir / "inputs";
    writeInputs(inputs);
    std::vector<CliRun> runs;
    std::vector<fs::path> outs;
    for (std::size_t i = 0; i < kCases.size(); ++i) {
        outs.push_back(dir / ("out-" + std::to_string(i)));
        std::vector<std::string> args;
        for (const auto& a : kCases[i].args) args.push_back(expand(a, inputs, outs.back()));
        runs.push_back({args, {{"HYBRIDLAB_ASSETS", std::nullopt}}});
    }
    const std::vector<CliResult> results = test::runHybridlabAll(runs);
    for (std::size_t i = 0; i < kCases.size(); ++i) {
        const CliResult& r = results[i];
        SCOPED_TRACE("case " + std::to_string(i) + ": " + kCases[i].message);
        EXPECT_EQ(r.exitStatus, kCases[i].exitStatus) << r.err;
        EXPECT_EQ(r.out, "") << "bad input prints nothing on stdout";
        EXPECT_EQ(r.err.rfind("hybridlab: error: ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one message, one line: " << r.err;
        EXPECT_CONTAINS(r.err, expand(kCases[i].message, inputs, outs[i]));
        EXPECT_FALSE(fs::exists(outs[i])) << "nothing written: " << outs[i];
    }
}

}  // namespace
}  // namespace hybridlab
