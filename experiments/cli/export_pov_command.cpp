// `hybridlab export-pov`: the scene of one frame as a POV-Ray 3.7 scene file, for the independent
// check of the Whitted reference (common/raytrace/pov_export.h).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "common/raytrace/pov_export.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "common/core/cli_number_validators.h"
#include "common/core/input_error.h"
#include "experiments/cli/commands.h"
#include "experiments/cli/view_options.h"

namespace hybridlab::cli {

namespace {

struct ExportPovOptions {
    ViewOptions view;
    std::string out;
};

void run(const ExportPovOptions& o) {
    std::error_code error;
    if (std::filesystem::is_directory(o.out, error)) throw InputError("--out " + o.out + ": a folder, expected a .pov file name");
    Scene scene = loadSceneFile(findSceneFile(o.view.scene));
    View view = o.view.resolve(scene);
    PovExport result = writePovScene(scene, view.camera, view.time, o.view.width, o.view.height, o.out);
    for (const auto& a : result.approximations) std::fprintf(stderr, "note: not exact in POV-Ray: %s\n", a.c_str());
    std::printf("scene %s, view %s, time %.4g s\n", scene.name.c_str(), view.label.c_str(), view.time);
    for (const auto& f : result.files) std::printf("wrote %s\n", f.string().c_str());
    const std::filesystem::path folder = result.files.front().parent_path();
    std::printf("render with (in %s):\n  povray", folder.empty() ? "the current folder" : folder.string().c_str());
    const std::filesystem::path pov = result.files.front().filename();
    for (const auto& a : povrayArguments(pov, std::filesystem::path(pov).replace_extension(".png"), o.view.width, o.view.height))
        std::printf(" %s", a.c_str());
    std::printf("\n");
}

}  // namespace

void addExportPovCommand(CLI::App& app) {
    auto o = std::make_shared<ExportPovOptions>();
    auto* cmd = app.add_subcommand("export-pov", "Write one frame's scene as a POV-Ray 3.7 scene file (with its textures as "
                                                 "linear PNGs beside it), to check the Whitted reference against POV-Ray");
    o->view.addTo(cmd, " (sets the aspect ratio)");
    cmd->add_option("--out", o->out, "Output POV-Ray scene file (.pov)")->required()->check(nonEmpty("a .pov file name"));
    cmd->callback([o] { run(*o); });
}

}  // namespace hybridlab::cli
