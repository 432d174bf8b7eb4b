#include "common/scene/assets.h"

#include <cstdlib>

namespace hybridlab {
namespace fs = std::filesystem;

bool isAssetPath(const std::string& path) { return path.rfind("assets/", 0) == 0; }

std::optional<fs::path> assetsRoot() {
    const char* v = std::getenv(kAssetsEnvVar);
    if (!v || !*v) return std::nullopt;
    return fs::path(v);
}

fs::path resolveScenePath(const std::string& path, const fs::path& sceneFile) {
    if (isAssetPath(path)) {
        auto root = assetsRoot();
        fs::path rest = fs::path(path).lexically_relative("assets");
        // Unset: no path at all, rather than a look in the current folder.
        return root ? *root / rest : fs::path();
    }
    fs::path p(path);
    return p.is_absolute() ? p : sceneFile.parent_path() / p;
}

std::string missingAssetExplanation(const std::string& path, const fs::path& resolved) {
    if (isAssetPath(path) && !assetsRoot()) {
        return "'" + path + "' is an asset, but " + kAssetsEnvVar +
               " is not set; set it to the folder holding the test-scene assets (../shared/assets in CI; "
               "its README.md lists where each model comes from)";
    }
    std::string s = "'" + path + "' not found (looked for " + resolved.string() + ")";
    if (isAssetPath(path)) {
        s += "; " + std::string(kAssetsEnvVar) + "=" + assetsRoot()->string() +
             " does not hold it: the assets README.md lists where each model comes from";
    }
    return s;
}

}  // namespace hybridlab
