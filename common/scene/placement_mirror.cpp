#include "common/scene/placement_mirror.h"

#include <glm/gtc/matrix_transform.hpp>

namespace hybridlab {

glm::vec3 scaleSigns(glm::vec3 scale) {
    return {scale.x < 0.0f ? -1.0f : 1.0f, scale.y < 0.0f ? -1.0f : 1.0f, scale.z < 0.0f ? -1.0f : 1.0f};
}

glm::vec3 moveMirrorIntoMeshes(SceneObject& object, std::span<Mesh> meshes) {
    const glm::vec3 signs = scaleSigns(object.isAnimated() ? object.animation.scales.front() : object.transform.scale);
    if (signs == glm::vec3(1.0f)) return signs;
    const glm::mat4 d = glm::scale(glm::mat4(1.0f), signs);
    for (Mesh& m : meshes) transformMesh(m, d);
    object.deformation.direction *= signs;
    object.deformation.axis *= signs;
    object.transform.scale *= signs;
    for (glm::vec3& s : object.animation.scales) s *= signs;
    return signs;
}

}  // namespace hybridlab
