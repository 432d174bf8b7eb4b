#include "common/raster/light_record.h"

#include "common/raytrace/shading.h"

namespace hybridlab {

raster_records::LightData lightRecord(const Light& l, int firstShadowLayer, int shadowLayerCount) {
    const SpotCone cone = spotCone(l);
    const auto type = static_cast<float>(lightTypeCode(l.type));
    return {glm::vec4(l.color * l.intensity, type), glm::vec4(l.position, cone.cosInner), glm::vec4(l.direction, cone.cosOuter),
            glm::ivec4(firstShadowLayer, shadowLayerCount, 0, 0)};
}

}  // namespace hybridlab
