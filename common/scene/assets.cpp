#include "common/scene/assets.h"

#include <cstdlib>

#include "common/scene/scene_catalog.h"

namespace hybridlab {
namespace fs = std::filesystem;

bool isAssetPath(const std::string& path) { return path.rfind("assets/", 0) == 0; }

std::optional<fs::path> assetsOverride() {
    const char* v = std::getenv(kAssetsEnvVar);
    if (!v || !*v) return std::nullopt;
    return fs::path(v);
}

fs::path assetsRoot(const fs::path& sceneFile) {
    if (auto root = assetsOverride()) return *root;
    std::error_code ec;
    fs::path beside = sceneFile.parent_path() / "assets";
    if (fs::is_directory(beside, ec)) return beside;
    return scenesDirectory() / "assets";
}

fs::path resolveScenePath(const std::string& path, const fs::path& sceneFile) {
    if (isAssetPath(path)) return assetsRoot(sceneFile) / fs::path(path).lexically_relative("assets");
    fs::path p(path);
    return p.is_absolute() ? p : sceneFile.parent_path() / p;
}

std::string missingAssetExplanation(const std::string& path, const fs::path& resolved) {
    std::string s = "'" + path + "' not found (looked for " + resolved.string() + ")";
    if (!isAssetPath(path)) return s;
    if (auto root = assetsOverride()) {
        return s + "; " + kAssetsEnvVar + "=" + root->string() +
               " does not hold it: unset it to use the repository's scenes/assets, whose README.md lists "
               "where each model comes from";
    }
    return s + ": the test-scene models are in the repository's scenes/assets (its README.md lists where "
               "each comes from); " +
           kAssetsEnvVar + " points elsewhere";
}

}  // namespace hybridlab
