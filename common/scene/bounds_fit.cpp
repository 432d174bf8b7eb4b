#include "common/scene/bounds_fit.h"

#include <algorithm>

namespace hybridlab {

glm::vec3 anchorPoint(const Aabb& bounds, BoundsFit::Anchor anchor) {
    glm::vec3 p = bounds.center();
    if (anchor == BoundsFit::Anchor::Bottom) p.y = bounds.lo.y;
    return p;
}

Aabb placedBounds(const Aabb& local, const Transform& placement) { return local.transformed(placement.matrix()); }

Transform fitToBounds(const Aabb& local, Transform placement, const BoundsFit& fit) {
    placement.position = glm::vec3(0.0f);
    // Bounds scale with a uniform factor, so one measurement gives it.
    const glm::vec3 extent = placedBounds(local, placement).extent();
    float factor = 1.0f;
    if (fit.height) factor = *fit.height / extent.y;
    else if (fit.size) factor = *fit.size / std::max({extent.x, extent.y, extent.z});
    placement.scale *= factor;
    placement.position = fit.at - anchorPoint(placedBounds(local, placement), fit.anchor);
    return placement;
}

}  // namespace hybridlab
