#include "common/scene/scene_catalog.h"

#include <algorithm>
#include <cstdlib>

#include "common/core/input_error.h"
#include "common/core/input_file.h"

namespace hybridlab {
namespace fs = std::filesystem;

fs::path scenesDirectory() {
    // A bundle (`hybridlab bundle`) carries its own scenes, away from the checkout it was built in.
    if (const char* v = std::getenv(kScenesEnvVar); v && *v) {
        // Set wrong, it would list no scenes and find none, as if there were none to find.
        std::error_code error;
        if (!fs::is_directory(v, error))
            throw InputError(std::string(kScenesEnvVar) + "=" + v + ": not a folder (a folder of scene files; unset it for the program's own)");
        return fs::path(v);
    }
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
    constexpr const char* kExpected = "a scene file (.toml) or a scene's name";
    const InputPathKind kind = inputPathKind(p);
    if (kind == InputPathKind::RegularFile) return p;
    if (kind != InputPathKind::Missing) requireInputFile(p, kExpected);  // a folder, a device, a loop of links
    if (p.extension() == ".toml" || nameOrPath.find('/') != std::string::npos) {
        throw InputError(nameOrPath + ": scene file not found");
    }
    fs::path named = scenesDirectory() / (nameOrPath + ".toml");
    if (inputPathKind(named) != InputPathKind::Missing) return named;
    std::string known;
    for (const auto& f : listSceneFiles()) known += (known.empty() ? "" : ", ") + f.stem().string();
    throw InputError("unknown scene '" + nameOrPath + "' (built-in scenes: " + known + "; or give a path to a .toml file)");
}

}  // namespace hybridlab
