#pragma once
// Where scene files find their models and textures (DESIGN.md "A frame, as data"): paths
// "assets/<folder>/<file>" resolve against the folder in HYBRIDLAB_ASSETS; other relative paths
// resolve against the scene file's folder.
#include <filesystem>
#include <optional>
#include <string>

namespace hybridlab {

inline constexpr const char* kAssetsEnvVar = "HYBRIDLAB_ASSETS";

bool isAssetPath(const std::string& path);

// The asset folder from the environment, if set.
std::optional<std::filesystem::path> assetsRoot();

// Resolves `path` as written in `sceneFile`; does not check existence. An asset path with
// HYBRIDLAB_ASSETS unset resolves to an empty path (which never exists).
std::filesystem::path resolveScenePath(const std::string& path, const std::filesystem::path& sceneFile);

// Why an asset could not be found: where it looked, and where the models come from.
std::string missingAssetExplanation(const std::string& path, const std::filesystem::path& resolved);

}  // namespace hybridlab
