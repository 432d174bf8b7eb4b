#include "common/scene/transform.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/matrix_inverse.hpp>

namespace hybridlab {

glm::quat eulerDegreesToQuat(glm::vec3 degrees) {
    glm::vec3 r = glm::radians(degrees);
    glm::quat qx = glm::angleAxis(r.x, glm::vec3(1, 0, 0));
    glm::quat qy = glm::angleAxis(r.y, glm::vec3(0, 1, 0));
    glm::quat qz = glm::angleAxis(r.z, glm::vec3(0, 0, 1));
    return qz * qy * qx;
}

glm::mat4 Transform::matrix() const {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), position) * glm::mat4_cast(rotation);
    return glm::scale(m, scale);
}

glm::mat3 normalMatrix(const glm::mat4& m) { return glm::inverseTranspose(glm::mat3(m)); }

Aabb Aabb::transformed(const glm::mat4& m) const {
    Aabb out;
    if (!valid()) return out;
    for (int i = 0; i < 8; ++i) {
        glm::vec3 c((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
        out.extend(glm::vec3(m * glm::vec4(c, 1.0f)));
    }
    return out;
}

}  // namespace hybridlab
