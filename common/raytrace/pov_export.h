#pragma once
// Writes a scene as a POV-Ray 3.7 scene file (SDL), so that POV-Ray, an independent Whitted ray
// tracer, can check the reference (DESIGN.md "Invariants that tests hold"). The file reproduces
// the shading model of shading.h in POV-Ray's terms; pov_export.cpp says how, term by term, and
// where POV-Ray cannot follow exactly (those places are also listed in PovExport::approximations).
//
// Render it as the reference is rendered: linear 16-bit PNG, one ray through each pixel centre:
//   povray +W<w> +H<h> -D -A File_Gamma=1.0 +FN16 +I<scene.pov> +O<out.png>
#include <filesystem>
#include <string>
#include <vector>

#include "common/scene/scene.h"

namespace hybridlab {

struct PovExport {
    std::vector<std::filesystem::path> files;  // the .pov file, then the texture PNGs written beside it
    std::vector<std::string> approximations;   // where POV-Ray's image will differ from the shading model
};

// Writes `out` (.pov) with the objects placed at scene time `time`, seen by `camera` with the aspect
// ratio width / height, plus one linear 16-bit PNG per textured material beside it
// (<stem>.mat<i>.png). Throws InputError for what cannot be exported (a cube-map sky, a zero
// texture tiling, a bad size or file name) before anything is written; files are written to
// temporary names and renamed, so no partial output is left behind.
PovExport writePovScene(const Scene& scene, const Camera& camera, double time, int width, int height,
                        const std::filesystem::path& out);

// The povray arguments (without the program name) that render `pov` into `png` as above.
std::vector<std::string> povrayArguments(const std::filesystem::path& pov, const std::filesystem::path& png, int width,
                                         int height);

}  // namespace hybridlab
