#include "common/raster/gbuffer.h"

namespace hybridlab {

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
