#pragma once
// Where scene files find their models and textures (DESIGN.md "A frame, as data"): paths
// "assets/<folder>/<file>" resolve against the test-scene assets folder, other relative paths
// against the scene file's folder. The assets folder is HYBRIDLAB_ASSETS when set; otherwise the
// `assets/` folder beside the scene file when there is one (a scene in the scenes/ folder of any
// checkout reads that checkout's models), else the repository's scenes/assets.
#include <filesystem>
#include <optional>
#include <string>

namespace hybridlab {

inline constexpr const char* kAssetsEnvVar = "HYBRIDLAB_ASSETS";

bool isAssetPath(const std::string& path);

// The asset folder from the environment, if set.
std::optional<std::filesystem::path> assetsOverride();

// The asset folder a scene file's "assets/..." paths resolve against (see above).
std::filesystem::path assetsRoot(const std::filesystem::path& sceneFile);

// Resolves `path` as written in `sceneFile`; does not check existence.
std::filesystem::path resolveScenePath(const std::string& path, const std::filesystem::path& sceneFile);

// Why an asset could not be found: where it looked, and where the models come from.
std::string missingAssetExplanation(const std::string& path, const std::filesystem::path& resolved);

}  // namespace hybridlab
