// Bad input through the real program, one case a line: the arguments, the exit status (2: bad
// input, 3: a file that cannot be written), a fragment of the one-line message (with the
// file:line:column where there is a file), and nothing written: each case's output path (%o)
// must not exist afterwards. The inputs are written by the test into one folder (%d). The scene
// files fixtures/bad/*.toml and the glTF cases of test_cli_bad_input.cpp are the other half of
// the table.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/image/image_io.h"
#include "experiments/runner/run_record.h"
#include "tests/support/cli_runner.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/runner_checks.h"
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

// PNG's CRC-32 of a chunk's type and data.
std::uint32_t pngCrc(const std::string& bytes) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

// A PNG chunk: length, type, data, CRC.
std::string pngChunk(const std::string& type, const std::string& data) {
    const auto bigEndian = [](std::uint32_t v) {
        return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
    };
    return bigEndian(static_cast<std::uint32_t>(data.size())) + type + data + bigEndian(pngCrc(type + data));
}

// The second round of inputs that passed silently or crashed: an object scaled past any float
// bound, textures and a sky holding a NaN, loops of symbolic links, a device and an unreadable
// file where files were expected, a PNG whose header claims more pixels than its 1 KB can hold,
// technique parameters of the wrong type, runs listed twice, a scale that changes sign.
void writeHardeningInputs(const fs::path& d) {
    using test::writeTextFile;
    writeTextFile(d / "huge-scale.toml", sceneText("", "primitive = \"sphere\"\nscale = 1e38\n"));
    writeTextFile(d / "sign-change.toml",
                  sceneText("", "primitive = \"cube\"\nanimation = { keys = [{ time = 0.0, scale = 1.0 }, { time = 1.0, scale = [1.0, -1.0, 1.0] }] }\n"));
    Image nan(4, 4, glm::vec4(0.5f));
    nan.at(2, 1).g = std::numeric_limits<float>::quiet_NaN();
    nan.at(3, 3).r = std::numeric_limits<float>::infinity();
    writeExr(d / "nan-texel.exr", nan);
    writeExr(d / "finite.exr", Image(4, 4, glm::vec4(0.5f)));
    writeTextFile(d / "nan-texture.toml", sceneText("diffuse_texture = \"nan-texel.exr\"\n", "primitive = \"cube\"\n"));
    writeTextFile(d / "nan-sky.toml", sceneText("", "primitive = \"cube\"\n") +
                                          "\n[sky]\ncube_map = [\"finite.exr\", \"finite.exr\", \"nan-texel.exr\", \"finite.exr\", "
                                          "\"finite.exr\", \"finite.exr\"]\n");
    for (const char* ext : {".toml", ".glb"}) {
        fs::create_symlink(std::string("loop-b") + ext, d / (std::string("loop-a") + ext));
        fs::create_symlink(std::string("loop-a") + ext, d / (std::string("loop-b") + ext));
    }
    writeTextFile(d / "loop-model.toml", sceneText("", "model = \"loop-a.glb\"\n"));
    // 16384 x 16384 RGB in 1 KB: 805 MB of pixels that a decoder would allocate before finding the
    // data missing.
    const std::string ihdr = std::string{0, 0, 0x40, 0, 0, 0, 0x40, 0, 8, 2, 0, 0, 0};
    std::string png = "\x89PNG\r\n\x1a\n" + pngChunk("IHDR", ihdr) + pngChunk("IDAT", std::string(960, '\0')) + pngChunk("IEND", "");
    writeTextFile(d / "huge.png", png);
    writeTextFile(d / "huge-png.toml", sceneText("diffuse_texture = \"huge.png\"\n", "primitive = \"cube\"\n"));
    const std::string scene = "[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[32, 32]]\n";
    writeTextFile(d / "param-string.toml", scene + "\n[[techniques]]\nname = \"whitted\"\nparams = { max_depth = \"3\" }\n");
    writeTextFile(d / "param-float.toml", scene + "\n[[techniques]]\nname = \"whitted\"\nparams = { max_depth = 2.0 }\n");
    writeTextFile(d / "scene-twice.toml", scene + scene + "\n[[techniques]]\nname = \"whitted\"\n");
    writeTextFile(d / "sets-twice.toml", scene + "\n[[techniques]]\nname = \"whitted\"\nparam_sets = [{ max_depth = 2 }, { max_depth = 2 }]\n");
    writeTextFile(d / "loop-scene.toml", "[[scenes]]\nscene = \"loop-a.toml\"\nresolutions = [[32, 32]]\n\n[[techniques]]\nname = \"whitted\"\n");
}

// The third round, inputs that crashed in Embree or in FLIP: cameras whose view comes out NaN
// (an up vector of 0, a position beyond every coordinate bound, a path through its own look_at
// point, keys closer than the interpolation's differences can divide, a glTF camera node scaled
// to 0 or with no field of view), an object scaled to 1e-30, and a sky of faces of two sizes.
void writeThirdRoundInputs(const fs::path& d) {
    using test::writeTextFile;
    const std::string box = sceneText("", "primitive = \"cube\"\n");
    writeTextFile(d / "camera-up-zero.toml", box + "up = [0.0, 0.0, 0.0]\n");
    std::string far = box;
    far.replace(far.find("position = [0.0, 1.0, 5.0]"), 26, "position = [1e30, 1.0, 5.0]");
    writeTextFile(d / "camera-far.toml", far);
    const auto path = [&](const std::string& name, const std::string& keys) { return box + "\n[camera_paths." + name + "]\n" + keys; };
    writeTextFile(d / "key-spacing.toml", path("close", "keys = [\n"
                                                        "  { time = 0.0, position = [0.0, 1.0, 5.0], look_at = [0.0, 0.0, 0.0] },\n"
                                                        "  { time = 1e-9, position = [1.0, 1.0, 5.0], look_at = [0.0, 0.0, 0.0] },\n]\n"));
    writeTextFile(d / "through-look-at.toml", path("through", "interpolation = \"linear\"\nfps = 10.0\nkeys = [\n"
                                                              "  { time = 0.0, position = [0.0, 1.0, -5.0], look_at = [0.0, 1.0, 0.0] },\n"
                                                              "  { time = 2.0, position = [0.0, 1.0, 5.0], look_at = [0.0, 1.0, 0.0] },\n]\n"));
    writeTextFile(d / "tiny-scale.toml", sceneText("", "primitive = \"sphere\"\nscale = [1e-30, 1.0, 1.0]\n"));
    writeExr(d / "small.exr", Image(2, 2, glm::vec4(0.5f)));
    writeTextFile(d / "sky-sizes.toml", box + "\n[sky]\ncube_map = [\"finite.exr\", \"finite.exr\", \"small.exr\", \"finite.exr\", "
                                              "\"finite.exr\", \"finite.exr\"]\n");
    for (const auto& [name, yfov, scale] : {std::tuple{"camera-scale-zero", 0.8, 0.0}, std::tuple{"camera-no-fov", 0.0, 1.0}}) {
        test::GltfBuilder b;
        const int quad = b.addNode({{"mesh", b.addMesh("quad", b.addFloats(test::kTrianglePositions, "VEC3"))}});
        const int eye = b.addNode({{"name", "eye"}, {"camera", b.addPerspectiveCamera(yfov, 0.1, 100.0, 1.5)}, {"scale", {scale, scale, scale}}});
        b.setRoots({quad, eye});
        b.writeGltf(d / (std::string(name) + ".gltf"));
        writeTextFile(d / (std::string(name) + ".toml"), sceneText("", "model = \"" + std::string(name) + ".gltf\"\n"));
    }
    test::GltfBuilder shortMatrix;
    shortMatrix.setRoots({shortMatrix.addNode({{"name", "tri"}, {"matrix", {1.0, 0.0, 0.0}},
                                               {"mesh", shortMatrix.addMesh("tri", shortMatrix.addFloats(test::kTrianglePositions, "VEC3"))}})});
    shortMatrix.writeGltf(d / "short-matrix.gltf");
    writeTextFile(d / "short-matrix.toml", sceneText("", "model = \"short-matrix.gltf\"\n"));
    // A PNG whose header reads well and whose pixels end early: the config's check reads scenes
    // without decoding textures, so `run` meets it only once it renders, in a folder it made.
    writePng(d / "whole.png", Image(64, 64, glm::vec4(0.25f, 0.5f, 0.75f, 1.0f)));
    const std::string whole = test::readTextFile(d / "whole.png");
    writeTextFile(d / "truncated.png", whole.substr(0, whole.size() / 2));
    writeTextFile(d / "truncated-texture.toml", sceneText("diffuse_texture = \"truncated.png\"\n", "primitive = \"cube\"\n"));
    writeTextFile(d / "run-truncated.toml", "[[scenes]]\nscene = \"truncated-texture.toml\"\nresolutions = [[32, 32]]\n\n[[techniques]]\nname = \"raster\"\n");
    // Names that would make file names too long for a file system, or a folder outside results/.
    const std::string scene = "[[scenes]]\nscene = \"whitted-classic\"\nresolutions = [[32, 32]]\n";
    writeTextFile(d / "long-label.toml", scene + "\n[[techniques]]\nname = \"whitted\"\nlabel = \"" + std::string(300, 'a') + "\"\n");
    writeTextFile(d / "negative-light.toml", box + "\n[[lights]]\ntype = \"point\"\nposition = [0.0, 2.0, 0.0]\ncolor = [-1.0, 1.0, 1.0]\n");
    writeTextFile(d / "name-up.toml", "[experiment]\nname = \"../../up\"\n\n" + scene + "\n[[techniques]]\nname = \"whitted\"\n");
}

// Result sets made malformed, each a copy of fixtures/result_sets/verdict (records, images; no
// config.toml) with one file changed, and one copy whole: a results.json that is empty, holds no records, or a record
// of width 0, without a label, with a negative frame time or a label longer than any file name; an
// experiment.json that is not JSON or whose metric table shows -5 decimals; a config.toml that is
// not TOML; a record that names a missing image; a killed runner's record whose SSIM is a string.
void writeReportInputs(const fs::path& d) {
    using test::writeTextFile;
    const fs::path fixture = test::sourceDir() / "tests" / "fixtures" / "result_sets" / "verdict";
    const auto set = [&](const std::string& name) {
        fs::copy(fixture, d / name, fs::copy_options::recursive);
        return d / name;
    };
    const auto changeRecord = [&](const std::string& name, const std::function<void(nlohmann::json&)>& change) {
        const fs::path results = set(name) / "results.json";
        nlohmann::json records = nlohmann::json::parse(test::readTextFile(results));
        change(records[0]);
        writeTextFile(results, records.dump(1));
    };
    writeTextFile(set("results-empty") / "results.json", "");
    writeTextFile(set("results-none") / "results.json", "[]\n");
    changeRecord("width-zero", [](nlohmann::json& r) { r["width"] = 0; });
    changeRecord("no-label", [](nlohmann::json& r) { r.erase("label"); });
    changeRecord("negative-time", [](nlohmann::json& r) { r["frame_ms"]["median"] = -5.0; });
    changeRecord("long-label", [](nlohmann::json& r) { r["label"] = std::string(100000, 'L'); });
    changeRecord("missing-image", [](nlohmann::json& r) { r["images"]["exr"] = "images/nope.exr"; });
    writeTextFile(set("experiment-invalid") / "experiment.json", "{\n");
    const fs::path digits = set("metric-digits") / "experiment.json";
    nlohmann::json experiment = nlohmann::json::parse(test::readTextFile(digits));
    experiment["metric_table"] = nlohmann::json::parse(R"([{"key": "ssim", "label": "SSIM", "better": "higher", "range": [0.0, 1.0],
        "field": "ssim", "colormap": "viridis", "scored": true, "summarised": true, "digits": -5}])");
    writeTextFile(digits, experiment.dump(1));
    writeTextFile(set("config-invalid") / "config.toml", "[[[\n");
    const fs::path killed = set("killed-ssim-string");
    fs::remove(killed / "results.json");
    const fs::path run = killed / "runs" / "0002-raster.json";
    nlohmann::json record = nlohmann::json::parse(test::readTextFile(run));
    record["metrics"]["whole"]["ssim"] = "x";
    writeTextFile(run, record.dump(1));
    set("whole");
    writeTextFile(d / "a-file", "");
}

// Finished shards of a two-run experiment, rec-0 and rec-1, whose records and images `merge` joins
// (4 x 2 pixels, no error maps), and copies of them with one thing wrong, each named by what: a
// record that is not JSON, one whose id is not its file's name, one of a negative width, one whose
// frame (2^63) would wrap to 0 in an int, a run recorded by both shards, an image missing and one
// that is text, the first shard without its config, a partition that is a number, an images folder
// that is a loop of symbolic links. And a killed runner's set whose runs/ is a file, for `report`.
void writeRecordInputs(const fs::path& d) {
    using test::writeTextFile;
    const Image pixels(4, 2, glm::vec4(0.5f));
    const auto recordOf = [](int index) {
        RunRecord r;
        r.index = static_cast<std::size_t>(index);
        r.id = "run-" + std::to_string(index);
        r.scene = "whitted-classic";
        r.view = "camera";
        r.width = 4;
        r.height = 2;
        r.technique = r.label = "whitted";
        r.metrics = nlohmann::json::object();
        r.reference = {"ref", "references/ref.exr", "references/ref.png", std::nullopt, 1.0, false};
        r.images = {"images/" + r.id + ".exr", "images/" + r.id + ".png", std::nullopt, {}};
        return toJson(r);
    };
    const auto shard = [&](const fs::path& folder, int index) {
        fs::create_directories(folder / "runs");
        writeTextFile(folder / "experiment.json", "{\"name\": \"r\", \"config_hash\": \"" + std::string(64, 'c') +
                                                      "\", \"runs_total\": 2, \"shard\": {\"index\": " + std::to_string(index) +
                                                      ", \"count\": 2, \"partition\": \"estimated-cost\", \"runs\": 1}}\n");
        writeTextFile(folder / "config.toml", "[[scenes]]\nscene = \"whitted-classic\"\n");
        writeTextFile(folder / "runs" / ("run-" + std::to_string(index) + ".json"), recordOf(index).dump(1));
        for (const std::string& image : {"images/run-" + std::to_string(index), std::string("references/ref")}) {
            fs::create_directories((folder / image).parent_path());
            writeExr(folder / (image + ".exr"), pixels);
            writePng(folder / (image + ".png"), pixels);
        }
    };
    shard(d / "rec-0", 0);
    shard(d / "rec-1", 1);
    const auto variant = [&](const std::string& name, const std::string& of) {
        fs::copy(d / of, d / name, fs::copy_options::recursive);
        return d / name;
    };
    writeTextFile(variant("rec-broken", "rec-1") / "runs/run-1.json", "{");
    const auto changed = [&](const std::string& name, const std::function<void(nlohmann::json&)>& change) {
        nlohmann::json record = recordOf(1);
        change(record);
        writeTextFile(variant(name, "rec-1") / "runs/run-1.json", record.dump(1));
    };
    changed("rec-other-id", [](nlohmann::json& r) { r["id"] = "run-9"; });
    changed("rec-negative-width", [](nlohmann::json& r) { r["width"] = -4; });
    changed("rec-frame-wrap", [](nlohmann::json& r) { r["frame"] = 1ULL << 63; });
    writeTextFile(variant("rec-twice", "rec-1") / "runs/run-0.json", recordOf(0).dump(1));
    fs::remove(variant("rec-no-image", "rec-1") / "images/run-1.exr");
    writeTextFile(variant("rec-text-image", "rec-1") / "images/run-1.png", "not a PNG\n");
    fs::remove(variant("rec-no-config", "rec-0") / "config.toml");
    const fs::path partition = variant("rec-partition", "rec-1") / "experiment.json";
    std::string meta = test::readTextFile(partition);
    meta.replace(meta.find("\"estimated-cost\""), 16, "7");
    writeTextFile(partition, meta);
    fs::remove_all(variant("rec-images-loop", "rec-1") / "images");
    fs::create_symlink("images", d / "rec-images-loop" / "images");
    const fs::path killed = variant("runs-file", "rec-0");
    fs::remove_all(killed / "runs");
    writeTextFile(killed / "runs", "not a folder\n");
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
    writeHardeningInputs(d);
    writeThirdRoundInputs(d);
    writeReportInputs(d);
    writeRecordInputs(d);
}

struct BadInputCase {
    std::vector<std::string> args;  // "%d": the inputs' folder; "%o": this case's output path
    int exitStatus;
    std::string message;            // a fragment of the message, "%d" expanded
};

// `render` of `scene` at 32 x 24, then `extra`.
std::vector<std::string> renderScene(const std::string& scene, std::vector<std::string> extra) {
    std::vector<std::string> a = {"render", "--scene", scene, "--width", "32", "--height", "24"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

std::vector<std::string> render(std::vector<std::string> extra) { return renderScene("whitted-classic", std::move(extra)); }

const std::vector<BadInputCase> kCases = {
    // Numbers on the command line: finite, in range, within their type.
    {render({"--time", "nan", "--out", "%o/x.exr"}), 2, "--time: expected a finite number in [-1e+06, 1e+06], got nan"},
    {render({"--time", "inf", "--out", "%o/x.exr"}), 2, "--time: expected a finite number in [-1e+06, 1e+06], got inf"},
    {render({"--time", "1e300", "--out", "%o/x.exr"}), 2, "--time: expected a number in [-1e+06, 1e+06], got 1e300"},
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
    // The second round. An object scaled past every bound: refused by scene-info and render alike.
    {{"scene-info", "%d/huge-scale.toml"}, 2,
     "%d/huge-scale.toml:9:9: objects[0].scale: places the object's vertices up to 5e+37 from the origin, beyond the limit of 1e+12"},
    {renderScene("%d/huge-scale.toml", {"--out", "%o/x.exr"}), 2,
     "objects[0].scale: places the object's vertices up to 5e+37 from the origin"},
    {{"scene-info", "%d/sign-change.toml"}, 2, "objects[0].animation.keys[1].scale: expected each scale factor to keep the sign it has at the first keyframe"},
    // Non-finite texels, in a texture and in a sky's face: named with the file and the first texel,
    // by scene-info (which decodes float images to check them) and by render.
    {{"scene-info", "%d/nan-texture.toml"}, 2,
     "%d/nan-texture.toml:5:19: materials.grey.diffuse_texture: %d/nan-texel.exr: 2 non-finite texels (NaN or infinite), the first at (2, 1): (0.5, nan, 0.5, 0.5)"},
    {renderScene("%d/nan-texture.toml", {"--out", "%o/x.exr"}), 2,
     "materials.grey.diffuse_texture: %d/nan-texel.exr: 2 non-finite texels (NaN or infinite), the first at (2, 1)"},
    {renderScene("%d/nan-sky.toml", {"--out", "%o/x.exr"}), 2,
     "sky.cube_map: %d/nan-texel.exr: 2 non-finite texels (NaN or infinite), the first at (2, 1)"},
    // Paths that are no files: a loop of symbolic links (as scene, model and config entry), a device,
    // a file the system cannot read: the system's reason, never an internal error.
    {{"scene-info", "%d/loop-a.toml"}, 2, "%d/loop-a.toml: cannot be read (Too many levels of symbolic links)"},
    {renderScene("%d/loop-a.toml", {"--out", "%o/x.exr"}), 2,
     "%d/loop-a.toml: cannot be read (Too many levels of symbolic links)"},
    {{"scene-info", "%d/loop-model.toml"}, 2, "objects[0].model: 'loop-a.glb' cannot be read (%d/loop-a.glb: Too many levels of symbolic links)"},
    {{"run", "%d/loop-scene.toml", "--out", "%o"}, 2, "scenes[0].scene: %d/loop-a.toml: cannot be read (Too many levels of symbolic links)"},
    {{"scene-info", "/dev/null"}, 2, "/dev/null: is not a regular file (a device or a pipe), expected a scene file (.toml) or a scene's name"},
    {{"run", "/dev/null", "--out", "%o"}, 2, "/dev/null: is not a regular file (a device or a pipe), expected a TOML file"},
    {{"scene-info", "/proc/self/mem"}, 2, "/proc/self/mem: cannot be read (Input/output error)"},
    // A header claiming more pixels than its file can hold: refused before the pixels are allocated.
    {{"scene-info", "%d/huge-png.toml"}, 2,
     "materials.grey.diffuse_texture: %d/huge.png: cannot read image (PNG: header claims 16384x16384 pixels, which take at least 780336 bytes (deflate packs at most 1032 bytes of rows into one), more than the file's 1017"},
    {renderScene("%d/huge-png.toml", {"--out", "%o/x.exr"}), 2, "%d/huge.png: cannot read image (PNG: header claims 16384x16384 pixels"},
    // Numbers echoed as written.
    {{"render", "--scene", "whitted-classic", "--width", "99999999999999999999", "--height", "24", "--out", "%o/x.exr"}, 2,
     "--width: expected an integer in [1, 16384], got 99999999999999999999"},
    {{"run", "%d/param-float.toml", "--out", "%o"}, 2,
     "%d/param-float.toml:7:24: techniques[0].params.max_depth: technique whitted: parameter 'max_depth': expected an integer in [0, 64], got 2.0"},
    // A config's parameters are typed: a string is not an integer.
    {{"run", "%d/param-string.toml", "--out", "%o"}, 2,
     "%d/param-string.toml:7:24: techniques[0].params.max_depth: technique whitted: parameter 'max_depth': expected an integer in [0, 64], got the string \"3\""},
    // Runs listed twice would each render twice.
    {{"run", "%d/scene-twice.toml", "--out", "%o"}, 2,
     "%d/scene-twice.toml:4:1: scenes[1]: scene whitted-classic at 32x32, the scene's camera, is listed again (first in scenes[0])"},
    {{"run", "%d/sets-twice.toml", "--out", "%o"}, 2,
     "techniques[0].param_sets[1]: the settings max_depth=2 are, with the defaults filled in, those of techniques[0].param_sets[0] (max_depth=2)"},
    // The third round: cameras that would look along NaN, a scale that underflows, a sky's faces.
    {{"scene-info", "%d/camera-up-zero.toml"}, 2, "%d/camera-up-zero.toml:14:6: camera.up: expected a non-zero vector"},
    {renderScene("%d/camera-far.toml", {"--out", "%o/x.exr"}), 2,
     "%d/camera-far.toml:12:12: camera.position: expected each coordinate within 1e+12 of the origin, got [1e+30, 1, 5]"},
    {{"scene-info", "%d/key-spacing.toml"}, 2,
     "camera_paths.close.keys[1].time: keyframe times must be at least 1e-06 s apart (previous key is at 0, this one at 1e-09)"},
    {{"render", "--scene", "%d/through-look-at.toml", "--camera-path", "through", "--frame", "10", "--width", "32", "--height", "24", "--out", "%o/x.exr"}, 2,
     "%d/through-look-at.toml: camera path 'through' at 1 s: the camera is at the point it looks at, so it looks nowhere"},
    {renderScene("%d/tiny-scale.toml", {"--out", "%o/x.exr"}), 2,
     "%d/tiny-scale.toml:9:9: objects[0].scale: expected non-zero scale factors, each at least 1e-09 in magnitude, got [1e-30, 1, 1]"},
    {{"render", "--scene", "%d/sky-sizes.toml", "--technique", "raster", "--width", "32", "--height", "24", "--out", "%o/x.exr"}, 2,
     "sky.cube_map: expected six square faces of one size, got small.exr at 2 x 2 beside finite.exr at 4 x 4"},
    {{"scene-info", "%d/sky-sizes.toml"}, 2, "sky.cube_map: expected six square faces of one size, got small.exr at 2 x 2"},
    {renderScene("%d/camera-scale-zero.toml", {"--out", "%o/x.exr"}), 2,
     "objects[0].model: %d/camera-scale-zero.gltf: camera node 'eye': its transform scales an axis to 0 or to infinity"},
    {{"scene-info", "%d/camera-no-fov.toml"}, 2,
     "objects[0].model: %d/camera-no-fov.gltf: camera node 'eye': perspective.yfov (in degrees) 0 is outside [0.001, 179]"},
    {{"scene-info", "%d/short-matrix.toml"}, 2, "objects[0].model: %d/short-matrix.gltf: node 'tri': matrix has 3 numbers, expected 16"},
    {{"scene-info", "%d/negative-light.toml"}, 2, "lights[0].color: colours must not be negative"},
    {render({"--camera-path", "", "--out", "%o/x.exr"}), 2, "--camera-path: expected a camera path's name, got ''"},
    {render({"--param", "max_depth=2", "--param", "max_depth=3", "--out", "%o/x.exr"}), 2,
     "--param max_depth is given twice (max_depth=2, then max_depth=3); give it once"},
    // A run that meets bad input before recording anything leaves no folder behind.
    {{"run", "%d/run-truncated.toml", "--out", "%o", "--quiet"}, 2,
     "%d/truncated-texture.toml:5:19: materials.grey.diffuse_texture: %d/truncated.png: cannot decode image ("},
    {{"run", "%d/long-label.toml", "--out", "%o"}, 2,
     "%d/long-label.toml:7:9: techniques[0].label: label 'aaaaaaaaaaaaaaaaaaaaaaaa...' is 300 characters long; run file names take 1 to 64"},
    {{"run", "%d/name-up.toml", "--dry-run"}, 2,
     "%d/name-up.toml:2:8: experiment.name: expected a folder name for results/<name> (1 to 100 characters, no '/', '\\' or control "
     "characters, not '.' or '..'), got '../../up'"},
    // Numbers that reached Embree as NaN rays (bake-em's viewpoints), and an empty folder name.
    {{"bake-em", "--scene", "em-disocclusion", "--view-height", "nan", "--cache", "%o"}, 2,
     "--view-height: expected a finite number in [-1e+12, 1e+12], got nan"},
    {{"bench", "--scene", "whitted-classic", "--budget", "nan"}, 2, "--budget: expected a finite number in [1, 1e+18], got nan"},
    {{"merge", "--out", "", "%d/shard-a0", "%d/shard-a1"}, 2, "--out: expected a folder, got ''"},
    {{"bundle", "--out", ""}, 2, "--out: expected a folder, got ''"},
    {{"bake-em", "--scene", "em-disocclusion", "--layers", "5", "--max-layers", "1", "--cache", "%o"}, 2,
     "--max-layers 1 bounds the automatic choice (--layers 0); with --layers 5 it would be ignored"},
    {{"export-pov", "--scene", "whitted-classic", "--out", ""}, 2, "--out: expected a .pov file name, got ''"},
    {{"export-pov", "--scene", "whitted-classic", "--out", "%d/a-folder"}, 2, "--out %d/a-folder: a folder, expected a .pov file name"},
    // FLIP's viewing condition: its filters grow with it (10^10 asked for more memory than exists).
    {{"compare", "%d/finite.exr", "%d/finite.exr", "--ppd", "nan", "--out", "%o"}, 2, "--ppd: expected a finite number in [0.001, 1000], got nan"},
    {{"compare", "%d/finite.exr", "%d/finite.exr", "--ppd", "1e10", "--out", "%o"}, 2, "--ppd: expected a number in [0.001, 1000], got 1e10"},
    {{"compare", "%d/finite.exr", "%d/finite.exr", "--range", "nan", "--out", "%o"}, 2, "--range: expected a finite number in [1e-12, 1e+12], got nan"},
    // A result set's malformed file, named with the place in it; a report folder that cannot be written.
    {{"report", "%d/results-empty", "--out", "%o"}, 2, "%d/results-empty/results.json: not valid JSON (Expecting value at line 1, column 1)"},
    {{"report", "%d/results-none", "--out", "%o"}, 2, "%d/results-none/results.json: holds no records (expected at least one run)"},
    {{"report", "%d/width-zero", "--out", "%o"}, 2, "%d/width-zero/results.json: record 0: $.width: 0 is below the minimum 1"},
    {{"report", "%d/no-label", "--out", "%o"}, 2, "%d/no-label/results.json: record 0: $: missing required 'label'"},
    {{"report", "%d/negative-time", "--out", "%o"}, 2, "%d/negative-time/results.json: record 0: $.frame_ms.median: -5.0 is below the minimum 0"},
    {{"report", "%d/long-label", "--out", "%o"}, 2, "%d/long-label/results.json: record 0: $.label: expected at most 255 characters, got 100000"},
    {{"report", "%d/missing-image", "--out", "%o"}, 2, "%d/missing-image/images/nope.exr: "},
    {{"report", "%d/experiment-invalid", "--out", "%o"}, 2,
     "%d/experiment-invalid/experiment.json: not valid JSON (Expecting property name enclosed in double quotes at line 2, column 1)"},
    {{"report", "%d/metric-digits", "--out", "%o"}, 2, "%d/metric-digits/experiment.json: $.metric_table[0].digits: -5 is below the minimum 0"},
    {{"report", "%d/config-invalid", "--out", "%o"}, 2, "%d/config-invalid/config.toml: not valid TOML (Invalid initial character for a key part (at line 1, column 3))"},
    {{"report", "%d/killed-ssim-string", "--out", "%o"}, 2,
     "%d/killed-ssim-string/runs/0002-raster.json: $.metrics.whole.ssim: expected number or null, got \"x\""},
    {{"report", "%d/whole", "--out", "%d/a-file"}, 3, "%d/a-file: cannot be written (a file, not a folder)"},
    {{"report", "%d/whole", "--out", "/proc/hybridlab-no-such-folder/report"}, 3, "/proc/hybridlab-no-such-folder/report: cannot be written ("},
    // A result set's records and the files they name, as `merge`, `run --resume` and `report` read
    // them (results_store.h): refused naming the shard's own file, before anything is written.
    {{"merge", "--out", "%o", "%d/rec-0", "%d/rec-broken"}, 2, "%d/rec-broken/runs/run-1.json: [json.exception.parse_error.101] parse error"},
    {{"merge", "--out", "%o", "%d/rec-0", "%d/rec-other-id"}, 2,
     "%d/rec-other-id/runs/run-1.json: holds the record of run 'run-9', expected the run its name says, 'run-1'"},
    {{"merge", "--out", "%o", "%d/rec-0", "%d/rec-negative-width"}, 2,
     "%d/rec-negative-width/runs/run-1.json: results record $.width: expected an integer in [1, 16384], got -4"},
    {{"merge", "--out", "%o", "%d/rec-0", "%d/rec-frame-wrap"}, 2,
     "%d/rec-frame-wrap/runs/run-1.json: results record $.frame: expected an integer in [-1, 10000000], got 9223372036854775808"},
    {{"merge", "--out", "%o", "%d/rec-0", "%d/rec-twice"}, 2,
     "merge: run 'run-0' is recorded by two shards: %d/rec-0/runs/run-0.json and %d/rec-twice/runs/run-0.json"},
    {{"merge", "--out", "%o", "%d/rec-0", "%d/rec-no-image"}, 2,
     "%d/rec-no-image/images/run-1.exr: image file not found (named by %d/rec-no-image/runs/run-1.json)"},
    {{"merge", "--out", "%o", "%d/rec-0", "%d/rec-text-image"}, 2, "%d/rec-text-image/images/run-1.png: cannot read image ("},
    {{"merge", "--out", "%o", "%d/rec-no-config", "%d/rec-1"}, 2, "%d/rec-no-config/config.toml: file not found"},
    {{"merge", "--out", "%o", "%d/rec-0", "%d/rec-partition"}, 2, "%d/rec-partition/experiment.json: shard.partition: expected a string, got 7"},
    {{"merge", "--out", "%o", "%d/rec-0", "%d/rec-images-loop"}, 2, "%d/rec-images-loop/images: cannot be read (Too many levels of symbolic links)"},
    {{"report", "%d/runs-file", "--out", "%o"}, 2, "%d/runs-file/runs: is not a folder, expected the folder of the set's records (runs/<id>.json)"},
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
    // And the shards the record cases break, whole: they merge; on a full disk, with exit status 3,
    // naming the file under --out (not the temporary folder the set is built in), leaving nothing.
    const fs::path merged = dir / "merged", full = dir / "full";
    for (const auto& [out, limit] : {std::pair{merged, std::optional<std::string>()}, std::pair{full, std::optional<std::string>("0")}})
        runs.push_back({{"merge", "--out", out.string(), (inputs / "rec-0").string(), (inputs / "rec-1").string()}, {{"HYBRIDLAB_TEST_WRITE_LIMIT", limit}}});
    const std::vector<CliResult> results = test::runHybridlabAll(runs);
    const CliResult& whole = results[kCases.size()];
    EXPECT_EQ(whole.exitStatus, 0) << whole.err;
    EXPECT_EQ(test::readResults(merged).size(), 2u);
    const CliResult& diskFull = results[kCases.size() + 1];
    EXPECT_EQ(diskFull.exitStatus, 3) << diskFull.err;
    EXPECT_EQ(diskFull.err, "hybridlab: error: " + (full / "config.toml").string() + ": cannot write (No space left on device)\n");
    for (const fs::directory_entry& e : fs::directory_iterator(dir.path()))
        EXPECT_EQ(e.path().filename().string().rfind(".tmp-", 0), std::string::npos) << e.path();
    EXPECT_FALSE(fs::exists(full));
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
