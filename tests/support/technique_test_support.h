#pragma once
// Rendering a scene with a technique from the registry, as the runner does (prepare, then a
// frame), and the scene variants that technique comparisons use.
#include <string>
#include <utility>
#include <vector>

#include "common/scene/scene.h"
#include "techniques/technique.h"

namespace hybridlab::test {

using TechniqueParams = std::vector<std::pair<std::string, ParamValue>>;

// Renders `frames` frames (the technique keeps its state between them) and returns the last.
inline FrameResult renderFrame(const Scene& scene, const std::string& technique, const TechniqueParams& params, int width, int height,
                               int frames = 1) {
    SceneContext context(scene);
    auto t = createTechnique(technique, params);
    t->prepare(context);
    FrameResult result;
    for (int i = 0; i < frames; ++i) result = t->render(context, {scene.camera, 0.0, width, height});
    return result;
}

inline Image renderImage(const Scene& scene, const std::string& technique, const TechniqueParams& params, int width, int height) {
    return renderFrame(scene, technique, params, width, height).image;
}

// The scene with its diffuse textures removed: the raster filters textures over the pixel's
// screen-space derivatives, the reference over its ray cone, so on minified textures the two still
// differ a little by filtering alone.
inline Scene withoutTextures(Scene scene) {
    for (Material& m : scene.materials) m.diffuseTexture = kNoTexture;
    return scene;
}

}  // namespace hybridlab::test
