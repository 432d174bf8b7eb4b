#include "common/raster/gbuffer.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace hybridlab {

namespace {

// The inverse of octahedralEncode in shaders/gbuffer_encoding.glsl (Cigolle et al., JCGT 2014).
glm::vec3 octahedralDecode(float u, float v) {
    glm::vec3 n(u, v, 1.0f - std::abs(u) - std::abs(v));
    if (n.z < 0.0f) {
        const float x = (1.0f - std::abs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f);
        const float y = (1.0f - std::abs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f);
        n.x = x;
        n.y = y;
    }
    return glm::normalize(n);
}

}  // namespace

glm::vec3 GBuffer::geometricNormal(std::size_t i) const { return octahedralDecode(emission[i].w, ambient[i].w); }

Material GBuffer::materialAt(std::size_t i) const {
    Material m;
    m.name = "g-buffer texel";
    m.emission = glm::vec3(emission[i]);
    m.ambient = glm::vec3(ambient[i]);
    m.diffuse = glm::vec3(diffuse[i]);
    m.specular = glm::vec3(specular[i]);
    m.specularExponent = specular[i].w;
    m.reflectivity = optical[i].x;
    m.ior = optical[i].y;
    m.opacity = optical[i].z;
    m.fresnel = optical[i].w > 0.5f;
    return m;
}

std::vector<std::uint64_t> visiblePixelsFromIds(const GBuffer& g, std::size_t objectCount) {
    std::vector<std::uint64_t> counts(objectCount + 1, 0);
    for (std::uint32_t id : g.objectId) ++counts[id < counts.size() ? id : 0];
    counts.erase(counts.begin());  // the sky
    return counts;
}

}  // namespace hybridlab
