#pragma once
// The scene files that come with hybridlab (scenes/*.toml), found by name.
#include <filesystem>
#include <string>
#include <vector>

namespace hybridlab {

inline constexpr const char* kScenesEnvVar = "HYBRIDLAB_SCENES";

// The repository's scenes/, or HYBRIDLAB_SCENES when set.
std::filesystem::path scenesDirectory();

// Every scenes/*.toml, sorted by name.
std::vector<std::filesystem::path> listSceneFiles();

// `nameOrPath` is a file path (it exists, or ends in .toml) or the name of a file in scenes/.
// Throws InputError listing the known names when neither.
std::filesystem::path findSceneFile(const std::string& nameOrPath);

}  // namespace hybridlab
