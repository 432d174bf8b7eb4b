#include "common/raytrace/shading.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "common/image/cube_map_coordinate.h"

namespace hybridlab {

SpotCone spotCone(const Light& light) {
    return {std::cos(glm::radians(light.innerConeDegrees)), std::cos(glm::radians(light.outerConeDegrees))};
}

LightSample sampleLight(const Light& light, glm::vec3 p) { return sampleLight(light, spotCone(light), p); }

glm::vec3 skyRadiance(const Scene& scene, glm::vec3 d) {
    if (!scene.sky.hasCubeMap()) return scene.sky.color;
    const CubeMapCoordinate c = cubeMapCoordinate(d);
    const Image& img = scene.textures[scene.sky.cubeFaces[c.face]].image;
    const float u = c.st.x, v = c.st.y;
    // Clamp to the face instead of wrapping across its edge.
    float x = std::clamp(u * img.width(), 0.5f, img.width() - 0.5f) / img.width();
    float y = std::clamp(v * img.height(), 0.5f, img.height() - 0.5f) / img.height();
    return glm::vec3(img.sampleBilinearWrap(x, y));
}

}  // namespace hybridlab
