// `hybridlab render`: one frame of one technique, written as a linear EXR and a display PNG, with
// its stage times and ray counts.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

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
};

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

void run(const RenderOptions& o) {
    // Everything that can be wrong with the input is checked before rendering starts.
    auto [exrPath, pngPath] = outputPaths(o.out);
    std::vector<std::pair<std::string, ParamValue>> params;
    for (const auto& p : o.params) params.push_back(parseParamAssignment(p));
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

    std::printf("scene %s, technique %s, %dx%d, view %s, time %.4g s, %d threads\n", scene.name.c_str(), o.technique.c_str(),
                o.view.width, o.view.height, view.label.c_str(), view.time, o.threads > 0 ? o.threads : tbb::info::default_concurrency());
    std::printf("%-22s %10.3f ms\n", "prepare", prep.stages[0].milliseconds);
    for (const auto& s : result.stages) std::printf("stage %-16s %10.3f ms\n", s.name.c_str(), s.milliseconds);
    std::printf("%-22s %10.3f ms\n", "frame", result.totalMilliseconds());
    for (const auto& [name, value] : result.counters) std::printf("%-22s %12.0f\n", name.c_str(), value);
    if (auto it = result.counters.find("rays_total"); it != result.counters.end() && result.totalMilliseconds() > 0.0) {
        std::printf("%-22s %12.3f\n", "mrays_per_second", it->second / (result.totalMilliseconds() * 1e3));
    }
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
    cmd->callback([o] { run(*o); });
}

void addTechniquesCommand(CLI::App& app) {
    auto* cmd = app.add_subcommand("techniques", "List the techniques with their parameters, defaults and descriptions");
    auto json = std::make_shared<bool>(false);
    cmd->add_flag("--json", *json, "Print a JSON array of {name, description, parameters: [{name, type, default, description}]} instead");
    cmd->callback([json] {
        if (*json) {
            nlohmann::json out = nlohmann::json::array();
            for (const auto& t : registeredTechniques()) {
                nlohmann::json params = nlohmann::json::array();
                for (const auto& p : t.parameters) {
                    params.push_back({{"name", p.name}, {"type", p.typeDescription()}, {"default", parameterJson(p.defaultValue)},
                                      {"description", p.description}});
                }
                out.push_back({{"name", t.name}, {"description", t.description}, {"parameters", params}});
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
