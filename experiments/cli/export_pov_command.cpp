// `hybridlab export-pov`: the scene of one frame as a POV-Ray 3.7 scene file, for the independent
// check of the Whitted reference (common/raytrace/pov_export.h).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "common/raytrace/pov_export.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "common/scene/view.h"
#include "experiments/cli/commands.h"

namespace hybridlab::cli {

namespace {

struct ExportPovOptions {
    std::string scene;
    std::string cameraPath;
    std::optional<int> frame;
    std::optional<double> time;
    int width = 1280;
    int height = 720;
    std::string out;
};

void run(const ExportPovOptions& o) {
    Scene scene = loadSceneFile(findSceneFile(o.scene));
    View view = resolveView(scene, o.cameraPath, o.frame, o.time);
    PovExport result = writePovScene(scene, view.camera, view.time, o.width, o.height, o.out);
    for (const auto& a : result.approximations) std::fprintf(stderr, "note: not exact in POV-Ray: %s\n", a.c_str());
    std::printf("scene %s, view %s, time %.4g s\n", scene.name.c_str(), view.label.c_str(), view.time);
    for (const auto& f : result.files) std::printf("wrote %s\n", f.string().c_str());
    const std::filesystem::path folder = result.files.front().parent_path();
    std::printf("render with (in %s):\n  povray", folder.empty() ? "the current folder" : folder.string().c_str());
    const std::filesystem::path pov = result.files.front().filename();
    for (const auto& a : povrayArguments(pov, std::filesystem::path(pov).replace_extension(".png"), o.width, o.height))
        std::printf(" %s", a.c_str());
    std::printf("\n");
}

}  // namespace

void addExportPovCommand(CLI::App& app) {
    auto o = std::make_shared<ExportPovOptions>();
    auto* cmd = app.add_subcommand("export-pov", "Write one frame's scene as a POV-Ray 3.7 scene file (with its textures as "
                                                 "linear PNGs beside it), to check the Whitted reference against POV-Ray");
    cmd->add_option("--scene", o->scene, "Scene file, or the name of a built-in scene")->required();
    cmd->add_option("--camera-path", o->cameraPath, "Export the view from this camera path of the scene");
    cmd->add_option("--frame", o->frame, "Frame number on the camera path");
    cmd->add_option("--time", o->time, "Scene time in seconds (animation, and position on the camera path)");
    cmd->add_option("--width", o->width, "Image width (sets the aspect ratio)")->check(CLI::Range(1, 16384))->capture_default_str();
    cmd->add_option("--height", o->height, "Image height (sets the aspect ratio)")->check(CLI::Range(1, 16384))->capture_default_str();
    cmd->add_option("--out", o->out, "Output POV-Ray scene file (.pov)")->required();
    cmd->callback([o] { run(*o); });
}

}  // namespace hybridlab::cli
