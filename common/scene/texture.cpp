#include "common/scene/texture.h"

#include "common/core/input_error.h"
#include "common/image/color.h"
#include "common/image/image_io.h"
#include "common/image/non_finite_pixels.h"

namespace hybridlab {

bool isBuiltinTexture(const std::string& name) { return name == "builtin:checker"; }

Texture makeBuiltinTexture(const std::string& name) {
    if (name != "builtin:checker") throw InputError("unknown built-in texture '" + name + "' (expected builtin:checker)");
    constexpr int kSquares = 8, kSquarePixels = 64, kSize = kSquares * kSquarePixels;
    const glm::vec4 light(glm::vec3(srgbToLinear(0.9f)), 1.0f), dark(glm::vec3(srgbToLinear(0.15f)), 1.0f);
    Texture t{name, true, Image(kSize, kSize)};
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            t.image.at(x, y) = ((x / kSquarePixels + y / kSquarePixels) % 2 == 0) ? light : dark;
    return t;
}

Texture loadTexture(const std::filesystem::path& path, bool srgb) {
    Texture t{path.string(), srgb, readImage(path, srgb ? ColorEncoding::Srgb : ColorEncoding::Linear)};
    requireFiniteTexels(t.image, t.source);
    return t;
}

}  // namespace hybridlab
