// `hybridlab render`: one frame of one technique, written as a linear EXR and a display PNG, with
// its stage times and ray counts.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "common/core/atomic_file.h"
#include "common/core/input_error.h"
#include "common/image/image_io.h"
#include "common/image/non_finite_pixels.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "common/scene/view.h"
#include "experiments/cli/commands.h"
#include "experiments/cli/view_options.h"
#include "experiments/runner/parameter_json.h"
#include "techniques/stage_clock.h"
#include "techniques/technique.h"

namespace hybridlab::cli {

namespace fs = std::filesystem;

namespace {

struct RenderOptions {
    ViewOptions view;
    std::string technique = "whitted";
    std::string out;
    std::vector<std::string> params;
    int threads = 0;
    bool allCounters = false;
    bool json = false;
};

std::string timeText(double ms) {
    char text[64];
    std::snprintf(text, sizeof text, "%.3f ms", ms);
    return text;
}

// out.exr -> {out.exr, out.png}; out.png -> {out.exr, out.png}.
std::pair<fs::path, fs::path> outputPaths(const std::string& out) {
    fs::path p(out);
    std::string ext = p.extension().string();
    if (ext != ".exr" && ext != ".png") throw InputError("--out " + out + ": expected a .exr or .png file name");
    fs::path exr = p, png = p;
    exr.replace_extension(".exr");
    png.replace_extension(".png");
    for (const auto& f : {exr, png})
        if (fs::is_directory(f)) throw InputError("--out " + out + ": " + f.string() + " is a directory, expected an image file name");
    return {exr, png};
}

// A counter as the record holds it: a count as a whole number, a rate or a ratio to six
// significant digits (never rounded to a whole number: a hit rate of 0.232 is not 0).
std::string counterText(double value) {
    char text[64];
    if (value == std::floor(value) && std::fabs(value) < 1e15) std::snprintf(text, sizeof text, "%.0f", value);
    else std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

// The stage times and the counters in one aligned table; counters at 0 only with `allCounters`.
void printTimesAndCounters(double prepareMs, const FrameResult& result, bool allCounters) {
    std::vector<std::pair<std::string, std::string>> rows = {{"prepare", timeText(prepareMs)}};
    for (const auto& s : result.stages) rows.push_back({"stage " + s.name, timeText(s.milliseconds)});
    rows.push_back({"frame", timeText(result.totalMilliseconds())});
    std::size_t hidden = 0;
    for (const auto& [name, value] : result.counters) {
        if (value == 0.0 && !allCounters) ++hidden;
        else rows.push_back({name, counterText(value)});
    }
    if (auto it = result.counters.find("rays_total"); it != result.counters.end() && result.totalMilliseconds() > 0.0)
        rows.push_back({"mrays_per_second", counterText(std::round(it->second / (result.totalMilliseconds() * 1e3) * 1e3) / 1e3)});
    std::size_t nameWidth = 0, valueWidth = 0;
    for (const auto& [name, value] : rows) {
        nameWidth = std::max(nameWidth, name.size());
        valueWidth = std::max(valueWidth, value.size());
    }
    for (const auto& [name, value] : rows)
        std::printf("%-*s  %*s\n", static_cast<int>(nameWidth), name.c_str(), static_cast<int>(valueWidth), value.c_str());
    if (hidden > 0) std::printf("(%zu counters at 0 not shown: --all-counters)\n", hidden);
}

struct RenderSummary {
    std::string scene;
    std::string technique;
    int width;
    int height;
    const View& view;
    int threads;
    double prepareMs;
    const FrameResult& result;
};

// `render --json`: the same facts as the text, every counter included.
void printJson(const RenderSummary& r, const fs::path& exr, const fs::path& png) {
    nlohmann::json stages = nlohmann::json::object();
    for (const auto& s : r.result.stages) stages[s.name] = s.milliseconds;
    nlohmann::json j = {{"scene", r.scene},
                        {"technique", r.technique},
                        {"width", r.width},
                        {"height", r.height},
                        {"view", r.view.label},
                        {"time", r.view.time},
                        {"threads", r.threads},
                        {"prepare_ms", r.prepareMs},
                        {"stage_ms", stages},
                        {"frame_ms", r.result.totalMilliseconds()},
                        {"counters", r.result.counters},
                        {"files", {exr.string(), png.string()}}};
    std::printf("%s\n", j.dump(1).c_str());
}

void run(const RenderOptions& o) {
    // Everything that can be wrong with the input is checked before rendering starts.
    auto [exrPath, pngPath] = outputPaths(o.out);
    std::vector<std::pair<std::string, ParamValue>> params;
    for (const auto& p : o.params) {
        params.push_back(parseParamAssignment(p));
        for (std::size_t i = 0; i + 1 < params.size(); ++i)
            if (params[i].first == params.back().first)
                throw InputError("--param " + params.back().first + " is given twice (" + o.params[i] + ", then " + p + "); give it once");
    }
    auto technique = createTechnique(o.technique, params);
    Scene scene = loadSceneFile(findSceneFile(o.view.scene));
    View view = o.view.resolve(scene);
    if (!exrPath.parent_path().empty()) createDirectories(exrPath.parent_path());

    std::optional<tbb::global_control> threadLimit;
    if (o.threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, o.threads);

    SceneContext context(scene);
    FrameResult prep;
    StageClock prepClock(prep);
    technique->prepare(context);
    prepClock.lap("prepare");

    FrameRequest request{view.camera, view.time, o.view.width, o.view.height};
    FrameResult result = technique->render(context, request);

    writeImageAtomically(exrPath, result.image);
    writeImageAtomically(pngPath, result.image);
    if (const NonFinitePixels nonFinite = findNonFinite(result.image); nonFinite.count > 0)
        std::fprintf(stderr, "hybridlab: warning: %s: %s\n", exrPath.string().c_str(), nonFinite.description().c_str());

    const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
    if (o.json) {
        printJson(RenderSummary{scene.name, o.technique, o.view.width, o.view.height, view, threads, prep.stages[0].milliseconds, result},
                  exrPath, pngPath);
        return;
    }
    std::printf("scene %s, technique %s, %dx%d, view %s, time %.4g s, %d threads\n", scene.name.c_str(), o.technique.c_str(),
                o.view.width, o.view.height, view.label.c_str(), view.time, threads);
    printTimesAndCounters(prep.stages[0].milliseconds, result, o.allCounters);
    std::printf("wrote %s and %s\n", exrPath.string().c_str(), pngPath.string().c_str());
}

}  // namespace

void addRenderCommand(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    auto* cmd = app.add_subcommand("render", "Render one frame with one technique; writes a linear EXR and a display PNG");
    o->view.addTo(cmd);
    cmd->add_option("--technique", o->technique, "Technique name (see `hybridlab techniques`)")->capture_default_str();
    cmd->add_option("--out", o->out, "Output image, .exr or .png: both the linear EXR and the display PNG are written")->required();
    cmd->add_option("--param", o->params, "Technique parameter key=value (repeatable)");
    cmd->add_option("--threads", o->threads, "Worker threads (default: every core)")->check(CLI::Range(1, 1024));
    cmd->add_flag("--all-counters", o->allCounters, "Also print the counters that are 0");
    cmd->add_flag("--json", o->json, "Print {scene, technique, width, height, view, time, threads, prepare_ms, stage_ms, frame_ms, counters, "
                                     "files} as JSON instead");
    cmd->callback([o] { run(*o); });
}

void addTechniquesCommand(CLI::App& app) {
    auto* cmd = app.add_subcommand("techniques", "List the techniques with their parameters, defaults and descriptions");
    auto json = std::make_shared<bool>(false);
    cmd->add_flag("--json", *json, "Print a JSON array of {name, description, parameters: [{name, type, default, description}], search: [{parameter, values, scale, per_pixel, type}]} instead");
    cmd->callback([json] {
        if (*json) {
            nlohmann::json out = nlohmann::json::array();
            for (const auto& t : registeredTechniques()) {
                nlohmann::json params = nlohmann::json::array();
                for (const auto& p : t.parameters) {
                    params.push_back({{"name", p.name}, {"type", p.typeDescription()}, {"default", parameterJson(p.defaultValue)},
                                      {"description", p.description}});
                }
                // The knobs `tune` searches (techniques/search_space.h), with each value's type.
                nlohmann::json search = nlohmann::json::array();
                for (const auto& d : t.searchSpace) {
                    const auto spec = std::find_if(t.parameters.begin(), t.parameters.end(), [&](const ParamSpec& p) { return p.name == d.parameter; });
                    nlohmann::json values = nlohmann::json::array();
                    for (const auto& v : d.values) values.push_back(parameterJson(v));
                    search.push_back({{"parameter", d.parameter}, {"values", values}, {"scale", searchScaleName(d.scale)},
                                      {"per_pixel", d.perPixel}, {"type", spec == t.parameters.end()                  ? "unknown"
                                               : spec->type == ParamSpec::Type::Int   ? "int"
                                               : spec->type == ParamSpec::Type::Float ? "float"
                                               : spec->type == ParamSpec::Type::Bool  ? "bool"
                                                                                      : "choice"}});
                }
                out.push_back({{"name", t.name}, {"description", t.description}, {"parameters", params}, {"search", search}});
            }
            std::printf("%s\n", out.dump(1).c_str());
            return;
        }
        for (const auto& t : registeredTechniques()) {
            std::printf("%s\n    %s\n", t.name.c_str(), t.description.c_str());
            for (const auto& p : t.parameters) {
                std::printf("    --param %s=%s\n        %s (%s)\n", p.name.c_str(), formatParamValue(p.defaultValue).c_str(),
                            p.description.c_str(), p.typeDescription().c_str());
            }
            std::printf("\n");
        }
    });
}

}  // namespace hybridlab::cli
