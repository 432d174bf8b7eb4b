#pragma once
// Scene files (TOML). The format is documented in scenes/README.md. Any error throws InputError
// naming the file, line and column, the key and what was expected.
#include <filesystem>

#include "common/scene/scene.h"

namespace hybridlab {

struct SceneLoadOptions {
    // Skip decoding textures (for listings that only need counts and bounds).
    bool loadTextures = true;
};

Scene loadSceneFile(const std::filesystem::path& file, const SceneLoadOptions& options = {});

}  // namespace hybridlab
