#pragma once
// A scene and its mirror image through the plane x = 0, written as scene files: every object's
// position, rotation and scale mirrored (its x scale factor negated, the glass ball's scale -1.6
// all round, as the ball is round), the lights mirrored, the camera on the plane looking along it,
// and a sky that is its own mirror image. Rendered, the mirrored scene must give the plain scene's
// image flipped left to right: every path must take the outside of a mirrored object's triangles
// from their normals, not their reversed winding.
#include <filesystem>
#include <string>

#include <glm/geometric.hpp>

#include "common/image/image.h"
#include "common/image/image_io.h"
#include "tests/support/test_support.h"

namespace hybridlab::test {

struct MirroredScenes {
    std::filesystem::path plain, mirrored;
};

// Writes both scene files and the sky's six faces into `dir`.
inline MirroredScenes writeMirroredScenes(const std::filesystem::path& dir) {
    // The sky: a colour of the direction's y and z only, so that it is its own mirror image.
    constexpr int kFace = 16;
    const char* const faces[6] = {"sky-px.png", "sky-nx.png", "sky-py.png", "sky-ny.png", "sky-pz.png", "sky-nz.png"};
    for (int face = 0; face < 6; ++face) {
        Image image(kFace, kFace);
        for (int y = 0; y < kFace; ++y) {
            for (int x = 0; x < kFace; ++x) {
                const float sc = 2.0f * (static_cast<float>(x) + 0.5f) / kFace - 1.0f, tc = 2.0f * (static_cast<float>(y) + 0.5f) / kFace - 1.0f;
                // The inverse of cubeMapCoordinate's table (common/image/cube_map_coordinate.h).
                const glm::vec3 directions[6] = {{1, -tc, -sc}, {-1, -tc, sc}, {sc, 1, tc}, {sc, -1, -tc}, {sc, -tc, 1}, {-sc, -tc, -1}};
                const glm::vec3 d = glm::normalize(directions[face]);
                image.at(x, y) = glm::vec4(0.35f + 0.3f * d.y, 0.45f + 0.25f * d.z, 0.6f + 0.3f * d.y * d.z, 1.0f);
            }
        }
        writeDisplayPng(dir / faces[face], image);
    }
    const auto scene = [&](float s) {
        const auto x = [&](float v) { return std::to_string(s * v); };
        return std::string("[scene]\nname = \"") + (s > 0 ? "plain" : "mirrored") +
               "\"\nambient = [0.1, 0.1, 0.1]\n\n"
               "[sky]\ncube_map = [\"sky-px.png\", \"sky-nx.png\", \"sky-py.png\", \"sky-ny.png\", \"sky-pz.png\", \"sky-nz.png\"]\n\n"
               "[materials.glass]\ndiffuse = [0.0, 0.0, 0.0]\nspecular = [1.0, 1.0, 1.0]\nspecular_exponent = 80.0\nopacity = 0.0\n"
               "ior = 1.5\nfresnel = true\n\n"
               "[materials.floor]\ndiffuse = [0.8, 0.8, 0.8]\ndiffuse_texture = \"builtin:checker\"\ntexture_tiling = [3.0, 3.0]\n\n"
               "[materials.red]\ndiffuse = [0.8, 0.15, 0.1]\n\n[materials.blue]\ndiffuse = [0.1, 0.2, 0.8]\n\n"
               "[[objects]]\nname = \"floor\"\nprimitive = \"plane\"\nmaterial = \"floor\"\nposition = [0.0, -1.0, 0.0]\nscale = [" + x(8.0f) +
               ", 1.0, 8.0]\n\n"
               "[[objects]]\nname = \"ball\"\nprimitive = \"sphere\"\nmaterial = \"glass\"\nlens = true\nposition = [" + x(0.5f) +
               ", -0.1, 0.5]\nscale = " + x(1.6f) + "\n\n"
               "[[objects]]\nname = \"box\"\nprimitive = \"cube\"\nmaterial = \"red\"\nposition = [" + x(-1.4f) +
               ", -0.4, -1.2]\nrotation = [10.0, " + x(35.0f) + ", 0.0]\nscale = [" + x(0.8f) + ", 1.2, 0.8]\n\n"
               "[[objects]]\nname = \"post\"\nprimitive = \"cylinder\"\nmaterial = \"blue\"\nposition = [" + x(1.3f) +
               ", -0.3, -1.8]\nrotation = [0.0, 0.0, " + x(20.0f) + "]\nscale = [" + x(0.5f) + ", 1.4, 0.5]\n\n"
               "[[lights]]\ntype = \"point\"\nposition = [" + x(2.5f) + ", 4.0, 3.0]\nintensity = 20.0\n\n"
               "[[lights]]\ntype = \"directional\"\ndirection = [" + x(-0.3f) + ", -1.0, -0.2]\nintensity = 0.6\n\n"
               "[camera]\nposition = [0.0, 1.2, 5.0]\nlook_at = [0.0, -0.2, 0.0]\nfov_y = 45.0\n";
    };
    MirroredScenes files{dir / "plain.toml", dir / "mirrored.toml"};
    writeTextFile(files.plain, scene(1.0f));
    writeTextFile(files.mirrored, scene(-1.0f));
    return files;
}

// `image` flipped left to right.
inline Image flippedLeftToRight(const Image& image) {
    Image out(image.width(), image.height());
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) out.at(image.width() - 1 - x, y) = image.at(x, y);
    return out;
}

}  // namespace hybridlab::test
