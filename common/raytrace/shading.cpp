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

glm::vec3 reflectDirection(glm::vec3 d, glm::vec3 n) { return d - 2.0f * glm::dot(d, n) * n; }

bool refractDirection(glm::vec3 d, glm::vec3 n, float eta, glm::vec3& out) {
    float cosi = -glm::dot(d, n);
    float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
    if (k < 0.0f) return false;
    out = glm::normalize(eta * d + (eta * cosi - std::sqrt(k)) * n);
    return true;
}

float fresnelDielectric(float cosIncident, float n1, float n2) {
    float cosi = std::clamp(cosIncident, 0.0f, 1.0f);
    float sint2 = (n1 / n2) * (n1 / n2) * (1.0f - cosi * cosi);
    if (sint2 >= 1.0f) return 1.0f;
    float cost = std::sqrt(1.0f - sint2);
    float rs = (n1 * cosi - n2 * cost) / (n1 * cosi + n2 * cost);
    float rp = (n2 * cosi - n1 * cost) / (n2 * cosi + n1 * cost);
    return 0.5f * (rs * rs + rp * rp);
}

glm::vec3 compose(float om, float orr, glm::vec3 M, glm::vec3 R, glm::vec3 C, BlendRule rule) {
    glm::vec3 cm = om * M + (1.0f - om) * (orr * R + (1.0f - orr) * C);
    if (rule == BlendRule::Design) return cm;
    glm::vec3 cr = orr * R + (1.0f - orr) * (om * M + (1.0f - om) * C);  // Walewski eq. (6)
    return 0.5f * (cm + cr);
}

glm::vec3 uncomposeLocal(float om, float orr, glm::vec3 M, glm::vec3 R, glm::vec3 composite, glm::vec3 fallback, BlendRule rule) {
    const float slope = (1.0f - om) * (1.0f - orr);
    if (slope < 1e-4f) return fallback;
    return (composite - compose(om, orr, M, R, glm::vec3(0.0f), rule)) / slope;
}

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
