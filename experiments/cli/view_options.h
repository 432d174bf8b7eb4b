#pragma once
// The options that pick a scene, a view of it and an image size, shared by the commands that
// render or export one frame.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "common/scene/view.h"
#include "common/core/cli_number_validators.h"

namespace hybridlab::cli {

struct ViewOptions {
    std::string scene;
    std::string cameraPath;
    std::optional<int> frame;
    std::optional<double> time;
    int width = 1280;
    int height = 720;

    // --scene (required), --camera-path, --frame, --time, --width, --height.
    void addTo(CLI::App* cmd, const std::string& sizeNote = "") {
        cmd->add_option("--scene", scene, "Scene file, or the name of a built-in scene")->required();
        cmd->add_option("--camera-path", cameraPath, "A camera path of the scene (default: the scene's camera)")
            ->check(nonEmpty("a camera path's name"));
        cmd->add_option("--frame", frame, "Frame number on the camera path")->check(integerIn(0, limits::kFrame));
        cmd->add_option("--time", time, "Scene time in seconds (animation, and position on the camera path)")
            ->check(numberIn(-limits::kSceneTime, limits::kSceneTime));
        cmd->add_option("--width", width, "Image width" + sizeNote)->check(integerIn(1, limits::kImageSide))->capture_default_str();
        cmd->add_option("--height", height, "Image height" + sizeNote)->check(integerIn(1, limits::kImageSide))->capture_default_str();
    }

    View resolve(const Scene& s) const { return resolveView(s, cameraPath, frame, time); }
};

}  // namespace hybridlab::cli
