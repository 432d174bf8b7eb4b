#pragma once
// Textures of a scene, decoded to linear float RGBA on load.
#include <filesystem>
#include <string>

#include "common/image/image.h"

namespace hybridlab {

struct Texture {
    std::string source;  // the path or built-in name it came from
    bool srgb = true;    // was sRGB-encoded (colour textures); false for normal maps
    Image image;         // linear values
};

// Built-in procedural textures that need no files, named "builtin:<name>".
// builtin:checker is an 8 x 8 board of 64-pixel squares, light grey and dark grey.
bool isBuiltinTexture(const std::string& name);
Texture makeBuiltinTexture(const std::string& name);

Texture loadTexture(const std::filesystem::path& path, bool srgb);

}  // namespace hybridlab
