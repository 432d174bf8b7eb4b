#include "common/scene/scene_catalog.h"

#include <algorithm>
#include <cstdlib>

#include "common/core/input_error.h"

namespace hybridlab {
namespace fs = std::filesystem;

fs::path scenesDirectory() {
    // A bundle (`hybridlab bundle`) carries its own scenes, away from the checkout it was built in.
    if (const char* v = std::getenv(kScenesEnvVar); v && *v) return fs::path(v);
    return fs::path(HYBRIDLAB_SCENES_DIR);
}

std::vector<fs::path> listSceneFiles() {
    std::vector<fs::path> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(scenesDirectory(), ec))
        if (e.path().extension() == ".toml") out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

fs::path findSceneFile(const std::string& nameOrPath) {
    fs::path p(nameOrPath);
    if (fs::exists(p) && fs::is_regular_file(p)) return p;
    if (fs::is_directory(p)) throw InputError(nameOrPath + ": is a directory, expected a scene file (.toml) or a scene's name");
    if (p.extension() == ".toml" || nameOrPath.find('/') != std::string::npos) {
        throw InputError(nameOrPath + ": scene file not found");
    }
    fs::path named = scenesDirectory() / (nameOrPath + ".toml");
    if (fs::exists(named)) return named;
    std::string known;
    for (const auto& f : listSceneFiles()) known += (known.empty() ? "" : ", ") + f.stem().string();
    throw InputError("unknown scene '" + nameOrPath + "' (built-in scenes: " + known + "; or give a path to a .toml file)");
}

}  // namespace hybridlab
