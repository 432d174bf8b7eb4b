#include "common/scene/camera.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "common/core/number_check.h"

namespace hybridlab {

glm::quat Camera::lookAtOrientation(glm::vec3 position, glm::vec3 target, glm::vec3 up) {
    glm::vec3 f = glm::normalize(target - position);
    // Fall back to another up vector when looking straight along it.
    if (std::abs(glm::dot(f, glm::normalize(up))) > 0.9999f) up = std::abs(f.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    glm::vec3 r = glm::normalize(glm::cross(f, up));
    glm::vec3 u = glm::cross(r, f);
    glm::mat3 basis(r, u, -f);  // columns: camera x, y, z in world space
    return glm::normalize(glm::quat_cast(basis));
}

bool withinSceneReach(glm::vec3 p) {
    for (int i = 0; i < 3; ++i)
        if (!(std::abs(p[i]) <= limits::kSceneCoordinate)) return false;  // also NaN
    return true;
}

bool Camera::placementUsable() const {
    return withinSceneReach(position) && std::isfinite(orientation.x) && std::isfinite(orientation.y) && std::isfinite(orientation.z) &&
           std::isfinite(orientation.w);
}

glm::mat4 Camera::view() const {
    glm::mat4 camToWorld = glm::translate(glm::mat4(1.0f), position) * glm::mat4_cast(orientation);
    return glm::inverse(camToWorld);
}

glm::mat4 Camera::projectionMatrix(float aspect) const {
    glm::mat4 p(0.0f);
    const float n = nearPlane, f = farPlane;
    if (projection == Projection::Perspective) {
        const float t = 1.0f / std::tan(glm::radians(fovYDegrees) * 0.5f);
        p[0][0] = t / aspect;
        p[1][1] = -t;               // y down
        p[2][2] = n / (f - n);      // reverse Z: z_ndc = n (f + z_v) / (-z_v (f - n)): 1 at -n, 0 at -f
        p[2][3] = -1.0f;
        p[3][2] = n * f / (f - n);
    } else {
        const float h = 0.5f * orthoHeight, w = h * aspect;
        p[0][0] = 1.0f / w;
        p[1][1] = -1.0f / h;
        p[2][2] = 1.0f / (f - n);   // z_ndc = (f + z_v) / (f - n): 1 at -n, 0 at -f
        p[3][2] = f / (f - n);
        p[3][3] = 1.0f;
    }
    return p;
}

Ray Camera::rayThroughNdc(glm::vec2 ndc, float aspect) const { return CameraRays(*this, aspect).throughNdc(ndc); }

}  // namespace hybridlab
