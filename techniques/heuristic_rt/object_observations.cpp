#include "techniques/heuristic_rt/object_observations.h"

#include <algorithm>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

namespace hybridlab {

std::vector<ObjectObservation> observeVisibleObjects(const Scene& scene, const std::vector<Aabb>& localBounds, double time,
                                                     const Camera& camera, float aspect,
                                                     const std::vector<std::uint64_t>& visiblePixels,
                                                     const std::vector<bool>& selectedLastFrame) {
    const glm::mat4 viewProj = camera.projectionMatrix(aspect) * camera.view();
    std::vector<ObjectObservation> observations;
    for (std::size_t o = 0; o < scene.objects.size() && o < visiblePixels.size(); ++o) {
        if (visiblePixels[o] == 0) continue;
        const SceneObject& object = scene.objects[o];
        const Aabb bounds = localBounds[o].transformed(object.worldMatrix(time));
        const glm::vec3 centre = 0.5f * (bounds.lo + bounds.hi);
        ObjectObservation obs;
        obs.object = static_cast<std::uint32_t>(o);
        obs.visiblePixels = static_cast<double>(visiblePixels[o]);
        const glm::vec4 clip = viewProj * glm::vec4(centre, 1.0f);
        // A centre behind the camera is as far from the image centre as it gets: P's floor.
        obs.boundsCenterNdc = clip.w > 0.0f ? glm::vec2(clip) / clip.w : glm::vec2(2.0f);
        // The camera inside the box: D would vanish; a millimetre keeps V finite.
        obs.distance = std::max(static_cast<double>(glm::length(centre - camera.position)), 1e-3);
        obs.refractive = scene.objectIsRefractive(o);
        obs.reflective = scene.objectIsReflective(o);
        obs.staticRelevance = object.relevance;
        obs.estimatedCost = object.cost;
        obs.selectedLastFrame = o < selectedLastFrame.size() && selectedLastFrame[o];
        observations.push_back(obs);
    }
    return observations;
}

}  // namespace hybridlab
