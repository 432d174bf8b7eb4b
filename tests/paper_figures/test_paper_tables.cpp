// The paper-table scripts of paper_figures/ on small result sets: Sabino 2012 Table 3
// (sabino_table3.py) must print each scene's size and the medians the records hold, and the gain
// as their ratio; de Macedo & Rodrigues Tables I-II (macedo_tables.py) a line per N with the
// dynamic triangles the ray scene updated, and the bvh_update stage's growth with them; the
// SSR speed table (ssr_speed_table.py) the ratios to whitted and the refractive trees' bound;
// Hakura & Snyder's Figure 8 (hakura_tables.py) the lens metrics at the views between viewpoint
// samples and their means over the path, and its EM resolution table; Walewski 2019 Tables 5-6
// (walewski_tables.py) run. Each prints the device the times were measured on under each table, and
// under its tables the paper scenes' counts beside the paper's (paper_figures/paper_scenes.py).
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "experiments/runner/device_record.h"
#include "experiments/runner/experiment_runner.h"
#include "tests/support/report_checks.h"
#include "tests/support/runner_checks.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Under every table of `text` (a block of lines starting with '|'), a blank line and the device the
// times were measured on: this machine's, as the runner recorded it.
void expectDeviceUnderEachTable(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    const std::string device = "Measured on: " + deviceRecord().at("vulkan_device").get<std::string>() + " [";
    std::size_t tables = 0;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].rfind("|", 0) != 0 || (i + 1 < lines.size() && lines[i + 1].rfind("|", 0) == 0)) continue;
        ++tables;
        ASSERT_LT(i + 2, lines.size()) << "nothing under the table ending at line " << i + 1;
        EXPECT_EQ(lines[i + 1], "");
        EXPECT_EQ(lines[i + 2].rfind(device, 0), 0u) << lines[i + 2];
        EXPECT_NE(lines[i + 2].find(deviceRecord().at("cpu_model").get<std::string>()), std::string::npos) << lines[i + 2];
    }
    EXPECT_GT(tables, 0u) << text;
}

// Runs the experiment `configText` into dir/results, then paper_figures/`script` on it; returns the
// table it wrote, having checked the device under each table.
std::string runAndTabulate(const test::TempDir& dir, const std::string& configText, const std::string& script) {
    const fs::path config = dir.path() / "config.toml";
    test::writeTextFile(config, configText);
    const RunnerOptions o = test::quietRunnerOptions(dir.path() / "results", dir.path() / "cache");
    EXPECT_TRUE(runExperiment(loadExperimentConfig(config), o).complete);
    const fs::path path = test::sourceDir() / "paper_figures" / script;
    const fs::path table = dir.path() / "table.md";
    const std::string command = "/usr/bin/python3 '" + path.string() + "' '" + o.outDir.string() + "' --out '" + table.string() + "' > /dev/null";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    const std::string text = test::readTextFile(table);
    expectDeviceUnderEachTable(text);
    return text;
}

std::vector<json> resultsOf(const test::TempDir& dir) { return test::readResults(dir.path() / "results"); }

// A record's rasterizer time as the table scripts sum it (report/results.py's raster_ms):
// the rasterizer frame's stages, in the record's (sorted) order.
double rasterizerMs(const json& record) {
    double ms = 0.0;
    for (const auto& [name, s] : record.at("stages").items()) {
        for (const char* r : {"shadow_maps", "gbuffer", "gbuffer.upload", "heuristic.visible_pixels", "lighting", "readback", "overhead"})
            if (name == r) ms += s.at("median").get<double>();
    }
    return ms;
}

// A count as the scene-count lines print it: thousands separated by commas ("16,968").
std::string withThousands(long count) {
    std::string digits = std::to_string(count);
    for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3) digits.insert(static_cast<std::size_t>(i), ",");
    return digits;
}

// `name here / paper (ratio)` for a large count of a scene-count line.
std::string countCell(const char* name, const json& stats, const char* key, long paper) {
    const long here = stats.at(key).get<long>();
    return std::string(name) + " " + withThousands(here) + " / " + withThousands(paper) + " (" +
           test::formatNumber("%.2fx", static_cast<double>(here) / static_cast<double>(paper)) + ")";
}

// The [experiment] table of the tests' configs: one timed frame per run, no warm-up, no optional images.
const std::string kOneFrameEach = "[experiment]\nwarmup_frames = 0\nrepeats = 1\nkeep = []\n";

// A procedural stand-in for a paper scene: a scene named `name` with a mirror ball and a glass one.
std::string standInScene(const std::string& name) {
    return "[scene]\nname = \"" + name + R"("
[materials.mirror]
diffuse = [0.05, 0.05, 0.05]
reflectivity = 0.9
[materials.glass]
diffuse = [0.8, 0.8, 0.8]
opacity = 0.1
ior = 1.5
[[objects]]
name = "ball"
primitive = "sphere"
slices = 16
stacks = 8
material = "mirror"
[[objects]]
name = "lens"
primitive = "sphere"
slices = 16
stacks = 8
material = "glass"
position = [1.5, 0.0, 0.0]
[[lights]]
type = "point"
position = [0, 4, 3]
intensity = 20.0
[camera]
position = [0.0, 1.0, 5.0]
look_at = [0.0, 0.0, 0.0]
)";
}

TEST(PaperTables, SabinoTable3HoldsTheHybridsStagesAndTheGain) {
    test::TempDir dir;
    const fs::path diningRoom = dir.path() / "dining-room.toml";
    test::writeTextFile(diningRoom, standInScene("dining-room"));
    const std::string text = runAndTabulate(dir, kOneFrameEach + R"(
[[scenes]]
scene = "whitted-classic"
resolutions = [[48, 27]]
[[scenes]]
scene = "cornell-mirror-glass"
resolutions = [[48, 27]]
[[scenes]]
scene = ')" + diningRoom.string() + R"('
resolutions = [[48, 27]]
[[techniques]]
name = "heuristic_rt"
label = "hybrid"
[[techniques]]
name = "rt_only"
label = "rt"
)",
                                             "sabino_table3.py");
    std::map<std::string, std::map<std::string, json>> runs;  // scene -> label -> record
    for (const auto& r : resultsOf(dir)) runs[r.at("scene")][r.at("label")] = r;
    ASSERT_EQ(runs.size(), 3u);
    for (const auto& [scene, byLabel] : runs) {
        SCOPED_TRACE(scene);
        const json &hybrid = byLabel.at("hybrid"), &rt = byLabel.at("rt");
        const double tHybrid = hybrid.at("frame_ms").at("median"), tRt = rt.at("frame_ms").at("median");
        const std::string row = "| " + scene + " | " + std::to_string(hybrid.at("scene_stats").at("vertices").get<int>()) + " | " +
                                std::to_string(hybrid.at("scene_stats").at("triangles").get<int>()) + " | " +
                                test::formatNumber("%.1f", rasterizerMs(hybrid)) + " | " + test::formatNumber("%.1f", tRt) + " | " +
                                test::formatNumber("%.1f", tHybrid) + " | " + test::formatNumber("%.2f", tRt / tHybrid) + " | ";
        EXPECT_NE(text.find(row), std::string::npos) << row << "\n" << text;
        EXPECT_GT(hybrid.at("scene_stats").at("triangles").get<int>(), 0);
    }
    // Under the table, the paper scene's counts beside Sabino's Table 4 (ratios here / paper), and why they differ;
    // whitted-classic and cornell-mirror-glass are the testbed's own, with no line.
    const json& stats = runs.at("dining-room").at("hybrid").at("scene_stats");
    const std::string counts = "- dining-room / Dining Room (Table 4): " + countCell("triangles", stats, "triangles", 224954) + ", " +
                               countCell("vertices", stats, "vertices", 386541) + "\n";
    EXPECT_NE(text.find("Scene counts, here / Sabino 2012 Tables 3 and 4:\n\n" + counts), std::string::npos) << counts << "\n" << text;
    EXPECT_NE(text.find("What differs and why: dining-room: the paper's is Brigade's demo scene"), std::string::npos) << text;
    EXPECT_EQ(text.find("- whitted-classic"), std::string::npos) << text;
}

// Walewski 2019 Tables 5 and 6 (walewski_tables.py) on a stand-in named sponza-spheres: under them,
// its counts beside Table 4's (ratios for the large ones), and why the scene differs.
TEST(PaperTables, WalewskiTablesHoldTheSceneCountsBesideTable4) {
    test::TempDir dir;
    const fs::path sponza = dir.path() / "sponza-spheres.toml";
    test::writeTextFile(sponza, standInScene("sponza-spheres"));
    const std::string text = runAndTabulate(dir, kOneFrameEach + R"(
[[scenes]]
scene = ')" + sponza.string() + R"('
resolutions = [[48, 27]]
[[techniques]]
name = "heuristic_rt"
label = "heuristic"
[[techniques]]
name = "heuristic_rt"
label = "no-heuristic"
params = { heuristic = false }
[[techniques]]
name = "rt_only"
[[techniques]]
name = "whitted"
)",
                                            "walewski_tables.py");
    const json stats = resultsOf(dir).at(0).at("scene_stats");
    EXPECT_EQ(stats.at("objects"), 2);
    const std::string counts = "- sponza-spheres / Sponza Spheres: " + countCell("triangles", stats, "triangles", 272144) + ", " +
                               countCell("vertices", stats, "vertices", 150704) + ", objects 2 / 29, reflective 1 / 3, refractive 1 / 23\n";
    EXPECT_NE(text.find("Scene counts, here / Walewski 2019 Table 4:\n\n" + counts), std::string::npos) << counts << "\n" << text;
    EXPECT_NE(text.find("What differs and why: sponza-spheres: the committed Sponza is the 66,444-triangle Dabrovic atrium"),
              std::string::npos) << text;
    EXPECT_LT(text.find("**Table 6**"), text.find("Scene counts")) << "the counts come under the tables";
}

// A procedural stand-in for teapots-deforming-N: N waving spheres in a ring around a mirror ball.
std::string deformingSpheres(int n) {
    return R"([scene]
name = "teapots-deforming-)" + std::to_string(n) + R"("
[materials.mirror]
diffuse = [0.05, 0.05, 0.05]
reflectivity = 0.9
[materials.matte]
diffuse = [0.7, 0.5, 0.3]
[[objects]]
name = "ball"
primitive = "sphere"
material = "mirror"
[[objects]]
name = "blob"
primitive = "sphere"
material = "matte"
position = [2.0, 0.0, 0.0]
scale = 0.6
[objects.deform]
amplitude = 0.1
wavelength = 0.5
speed = 1.0
[objects.copies]
count = )" + std::to_string(n) + R"(
[[lights]]
type = "point"
position = [0, 4, 3]
intensity = 20.0
[camera]
position = [0.0, 2.0, 6.0]
look_at = [0.0, 0.0, 0.0]
[camera_paths.orbit]
fps = 10
keys = [{ time = 0.0, position = [0.0, 2.0, 6.0], look_at = [0.0, 0.0, 0.0] }, { time = 0.3, position = [3.0, 2.0, 5.0], look_at = [0.0, 0.0, 0.0] }]
)";
}

TEST(PaperTables, MacedoTablesGrowTheBvhUpdateWithTheDeformedTriangles) {
    test::TempDir dir;
    std::string scenes;
    for (int n : {5, 10}) {
        const fs::path file = dir.path() / ("teapots-deforming-" + std::to_string(n) + ".toml");
        test::writeTextFile(file, deformingSpheres(n));
        scenes += "[[scenes]]\nscene = '" + file.string() + "'\nresolutions = [[48, 27]]\n[[scenes.views]]\npath = \"orbit\"\n";
    }
    const std::string text = runAndTabulate(
        dir, kOneFrameEach + scenes + "[[techniques]]\nname = \"ssr_fallback\"\n",
        "macedo_tables.py");
    EXPECT_NE(text.find("**Table II**"), std::string::npos) << text;
    EXPECT_EQ(text.find("**Table I**"), std::string::npos) << "no bunnies-falling-N runs, no Table I";
    // One line per N, its dynamic triangles the refitted copies' (N times one sphere's).
    std::map<int, double> refit;
    for (const auto& r : resultsOf(dir)) {
        const std::string scene = r.at("scene");
        refit[std::stoi(scene.substr(scene.rfind('-') + 1))] = r.at("counters").at("bvh_refit_triangles").get<double>();
    }
    ASSERT_EQ(refit.size(), 2u);
    EXPECT_GT(refit.at(5), 0.0);
    EXPECT_EQ(refit.at(10), 2.0 * refit.at(5));
    for (const auto& [n, triangles] : refit) {
        const std::string cells = "| " + std::to_string(n) + " | ";
        EXPECT_NE(text.find(cells), std::string::npos) << cells << "\n" << text;
        EXPECT_NE(text.find(test::formatNumber("%.1f", triangles / 1e3)), std::string::npos) << text;
    }
    for (const char* growth : {"Frame time of ssr_fallback: ", "Frame CPU time of ssr_fallback: ", "`bvh_update` of ssr_fallback: "})
        EXPECT_NE(text.find(growth), std::string::npos) << growth << "\n" << text;
    // Beside them, the same fit over the paper's rows of Table II (mean frame time against its dynamic triangles).
    EXPECT_NE(text.find("Frame time of the paper's CUDA rows: 2.5 ms per 1000 dynamic triangles (+ 7.6 ms), correlation 0.999, "
                        "largest N / smallest 3.40x"), std::string::npos) << text;
    EXPECT_NE(text.find("Frame time of the paper's OptiX rows: 6.8 ms per 1000 dynamic triangles"), std::string::npos) << text;
    // Under the table, each scene's counts beside Table II's (x10^3, the paper's to one decimal): the
    // record's scene_stats triangles and the ray scene's refitted triangles; then what differs.
    const std::map<int, std::pair<double, double>> paper = {{5, {3.0, 2.8}}, {10, {5.9, 5.7}}};
    for (const auto& r : resultsOf(dir)) {
        const std::string scene = r.at("scene");
        const int n = std::stoi(scene.substr(scene.rfind('-') + 1));
        const double triangles = r.at("scene_stats").at("triangles").get<double>(), dynamic = refit.at(n);
        const auto [paperTriangles, paperDynamic] = paper.at(n);
        const std::string line = "- " + scene + " / Table II, " + std::to_string(n) + " Utah teapots: triangles " +
                                 test::formatNumber("%.2fk", triangles / 1e3) + " / " + test::formatNumber("%.1fk", paperTriangles) + " (" +
                                 test::formatNumber("%.2fx", triangles / (paperTriangles * 1e3)) + "), dynamic triangles " +
                                 test::formatNumber("%.2fk", dynamic / 1e3) + " / " + test::formatNumber("%.1fk", paperDynamic) + " (" +
                                 test::formatNumber("%.2fx", dynamic / (paperDynamic * 1e3)) + ")\n";
        EXPECT_NE(text.find(line), std::string::npos) << line << "\n" << text;
    }
    EXPECT_NE(text.find("Scene counts, here / de Macedo & Rodrigues Tables I and II:"), std::string::npos) << text;
    EXPECT_NE(text.find("What differs and why: teapots-deforming-N: the teapot is the closed Utah teapot simplified to 572 triangles"),
              std::string::npos) << text;
}

// The SSR speed table (ssr_speed_table.py): per ssr_fallback variant, whitted's and its frame
// times with their ratio, SSIM, hit rate and fallback rays as the records hold them; per glass-trees
// run, the largest speed-up whitted / (raster + ssr + trace).
TEST(PaperTables, SsrSpeedTableHoldsTheRatiosAndTheBound) {
    test::TempDir dir;
    const std::string text = runAndTabulate(dir, kOneFrameEach + R"(metrics = ["ssim"]
[[scenes]]
scene = "whitted-classic"
resolutions = [[64, 36]]
[[techniques]]
name = "whitted"
[[techniques]]
name = "ssr_fallback"
param_sets = [ { }, { importance_cutoff = 0.0 } ]
[[techniques]]
name = "ssr_fallback"
label = "glass-trees"
params = { fallback = "none", recursion = "single" }
)",
                                             "ssr_speed_table.py");
    double whitted = 0.0;
    for (const auto& r : resultsOf(dir))
        if (r.at("label") == "whitted") whitted = r.at("frame_ms").at("median");
    ASSERT_GT(whitted, 0.0);
    std::size_t variants = 0;
    for (const auto& r : resultsOf(dir)) {
        const auto stage = [&](const char* name) { return r.at("stages").at(name).at("median").get<double>(); };
        const double t = r.at("frame_ms").at("median");
        if (r.at("label") == "ssr_fallback") {
            ++variants;
            const std::string setting = r.at("parameters_text").get<std::string>().empty() ? "defaults" : r.at("parameters_text").get<std::string>();
            const std::string row = "| whitted-classic | 64x36 | " + setting + " | " + test::formatNumber("%.1f", whitted) + " | " +
                                    test::formatNumber("%.1f", t) + " | " + test::formatNumber("%.2f", whitted / t) + " | " +
                                    test::formatNumber("%.4f", r.at("metrics").at("whole").at("ssim")) + " | " +
                                    test::formatNumber("%.3f", r.at("counters").at("ssr_hit_rate")) + " | " +
                                    std::to_string(static_cast<long>(r.at("counters").at("fallback_rays").get<double>())) + " | ";
            EXPECT_NE(text.find(row), std::string::npos) << row << "\n" << text;
        } else if (r.at("label") == "glass-trees") {
            const double floor = rasterizerMs(r) + stage("ssr") + stage("trace");
            const std::string cells = test::formatNumber("%.1f", stage("trace")) + " | " +
                                      test::formatNumber("%.2f", stage("trace") / whitted) + " | " +
                                      test::formatNumber("%.2f", whitted / floor) + " | " + test::formatNumber("%.2f", whitted / rasterizerMs(r)) + " |";
            EXPECT_NE(text.find(cells), std::string::npos) << cells << "\n" << text;
        }
    }
    EXPECT_EQ(variants, 2u);
}

TEST(PaperTables, HakuraFigure8HoldsTheViewsBetweenSamplesAndThePathMeans) {
    test::TempDir dir;
    const std::string bake = "viewpoints = 2, bake_width = 24, bake_height = 18, supersampling = 1, em_size = 8";
    const std::string text = runAndTabulate(dir, kOneFrameEach + R"(metrics = ["ssim", "flip", "temporal"]
[reference]
params = { lens_model = "two_term" }
[[scenes]]
scene = "teapot-lens"
resolutions = [[64, 36]]
[[scenes.views]]
[[scenes.views]]
path = "circle"
frames = [3, 5]
stride = 1
[[techniques]]
name = "whitted"
label = "two-term-rt"
params = { lens_model = "two_term" }
[[techniques]]
name = "layered_em"
label = "lem-display"
params = { )" + bake + R"( }
[[techniques]]
name = "layered_em"
label = "lem-display-single"
params = { single_layer = true, viewpoint_blending = false, )" + bake + R"( }
[[techniques]]
name = "layered_em"
label = "lem-display-256"
params = { viewpoints = 2, bake_width = 24, bake_height = 18, supersampling = 1, em_size = 16 }
)",
                                            "hakura_tables.py");
    std::map<std::string, std::map<int, std::pair<double, double>>> lens;  // label -> circle frame -> (SSIM, FLIP)
    std::map<std::string, std::map<int, double>> temporal;                   // label -> circle frame -> on the lens pixels
    std::map<std::string, std::string> emResolution;                         // label -> "SSIM / FLIP" at the camera
    for (const auto& r : resultsOf(dir)) {
        const auto& m = r.at("metrics").at("masked");
        if (r.at("view") == "camera" && m.contains("ssim"))
            emResolution[r.at("label")] = test::formatNumber("%.4f", m.at("ssim").get<double>()) + " / " +
                                          test::formatNumber("%.4f", m.at("flip").at("mean").get<double>());
        if (r.at("view") != "circle") continue;
        lens[r.at("label")][r.at("frame").get<int>()] = {m.at("ssim").get<double>(), m.at("flip").at("mean").get<double>()};
        if (r.contains("temporal_error_masked")) temporal[r.at("label")][r.at("frame").get<int>()] = r.at("temporal_error_masked").get<double>();
    }
    // The temporal error on the lens pixels, frame by frame (into frames 4 and 5), then mean and max.
    EXPECT_NE(text.find("(mean |(T_k - T_k-1) - (R_k - R_k-1)|, lens pixels;"), std::string::npos) << text;
    for (const char* label : {"lem-display", "lem-display-single"}) {
        const auto& t = temporal[label];
        ASSERT_EQ(t.size(), 2u) << label;
        const std::string row = std::string("| ") + label + " | " + test::formatNumber("%.4f", t.at(4)) + " | " + test::formatNumber("%.4f", t.at(5)) +
                                " | " + test::formatNumber("%.4f", (t.at(4) + t.at(5)) / 2.0) + " | " +
                                test::formatNumber("%.4f", std::max(t.at(4), t.at(5))) + " |";
        EXPECT_NE(text.find(row), std::string::npos) << row << "\n" << text;
    }
    // Single-layer minus multi-layer, where popping shows as spikes.
    const auto &multi = temporal["lem-display"], &single = temporal["lem-display-single"];
    const std::string popping = "| lem-display-single minus lem-display | " + test::formatNumber("%+.4f", single.at(4) - multi.at(4)) + " | " +
                                test::formatNumber("%+.4f", single.at(5) - multi.at(5)) + " |";
    EXPECT_NE(text.find(popping), std::string::npos) << popping << "\n" << text;
    std::string between = "| between viewpoint samples (circle@4) |", mean = "| mean over circle frames 3-5 (3) |";
    for (const char* label : {"lem-display", "lem-display-single"}) {
        const auto& frames = lens[label];
        ASSERT_EQ(frames.size(), 3u) << label;
        double ssim = 0.0, flip = 0.0;
        for (const auto& [frame, v] : frames) {
            ssim += v.first / 3.0;
            flip += v.second / 3.0;
        }
        between += " " + test::formatNumber("%.4f", frames.at(4).first) + " / " + test::formatNumber("%.4f", frames.at(4).second) + " |";
        mean += " " + test::formatNumber("%.4f", ssim) + " / " + test::formatNumber("%.4f", flip) + " |";
    }
    EXPECT_NE(text.find("| view | lem-display | lem-display-single |"), std::string::npos) << text;
    EXPECT_NE(text.find(between), std::string::npos) << between << "\n" << text;
    EXPECT_NE(text.find(mean), std::string::npos) << mean << "\n" << text;
    const std::string figure8 = text.substr(0, text.find("**EM resolution**"));
    EXPECT_EQ(figure8.find("circle@3"), std::string::npos) << "frames 3 and 5 are not between samples";
    // The EM resolution table (hakura2001_em_size.toml): the display bake and its 256-texel variant side by side.
    const std::string emRow = "| 64x36 camera | " + emResolution["lem-display"] + " | " + emResolution["lem-display-256"] + " |";
    EXPECT_NE(text.find("| view | lem-display | lem-display-256 |"), std::string::npos) << text;
    EXPECT_NE(text.find(emRow), std::string::npos) << emRow << "\n" << text;
    // teapot-lens beside what the paper says of its scene, which gives no triangle, vertex or object counts.
    const json stats = resultsOf(dir).at(0).at("scene_stats");
    const std::string counts = "- teapot-lens / a glass teapot, a reflective cup, a ring of columns and distant walls: triangles " +
                               withThousands(stats.at("triangles").get<long>()) + " / not given, vertices " +
                               withThousands(stats.at("vertices").get<long>()) + " / not given, objects 14 / not given, reflective 1 / 1, "
                               "refractive 1 / 1\n";
    EXPECT_NE(text.find("Scene counts, here / Hakura & Snyder 2001 Section 6:\n\n" + counts), std::string::npos) << counts << "\n" << text;
    EXPECT_NE(text.find("What differs and why: teapot-lens: the paper gives no triangle, vertex or column counts"), std::string::npos) << text;
}

}  // namespace
}  // namespace hybridlab
