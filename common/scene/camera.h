#pragma once
// Perspective or orthographic camera. Right-handed world, y up; the camera looks down its local
// -Z axis. Projection matrices map to Vulkan clip space: x right, y down (row 0 of an image is the
// top), and reverse-Z depth in [0, 1] with the near plane at 1 and the far plane at 0 (Upchurch &
// Desbrun; Walewski 2019 §3.1).
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace hybridlab {

struct Ray {
    glm::vec3 origin;
    glm::vec3 direction;  // unit length
};

// Whether `p` is finite and within limits::kSceneCoordinate of the origin, as every vertex is: a
// camera, or the point it looks at, farther off loses every digit of its view's basis.
bool withinSceneReach(glm::vec3 p);

struct Camera {
    enum class Projection { Perspective, Orthographic };

    Projection projection = Projection::Perspective;
    glm::vec3 position{0.0f};
    glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // camera-to-world rotation
    float fovYDegrees = 45.0f;                      // perspective: vertical field of view
    float orthoHeight = 2.0f;                       // orthographic: view height in world units
    float nearPlane = 0.05f;
    float farPlane = 1000.0f;

    static glm::quat lookAtOrientation(glm::vec3 position, glm::vec3 target, glm::vec3 up = {0, 1, 0});
    // Whether rays can leave it: its position withinSceneReach, its orientation finite. Past that,
    // its rays come out NaN.
    bool placementUsable() const;

    glm::vec3 forward() const { return orientation * glm::vec3(0, 0, -1); }
    glm::vec3 up() const { return orientation * glm::vec3(0, 1, 0); }
    glm::vec3 right() const { return orientation * glm::vec3(1, 0, 0); }

    glm::mat4 view() const;
    glm::mat4 projectionMatrix(float aspect) const;

    // The ray through a point of the image plane given in normalised device coordinates
    // (x right, y down, both in [-1, 1]); for pixel (px, py) of a W x H image pass
    // ((px + 0.5) / W * 2 - 1, (py + 0.5) / H * 2 - 1).
    Ray rayThroughNdc(glm::vec2 ndc, float aspect) const;
};

// Rays through many points of one camera's image plane: Camera::rayThroughNdc with the frame's
// constants (tan(fov_y / 2) for a perspective camera) taken once, not once a pixel.
class CameraRays {
public:
    CameraRays(const Camera& camera, float aspect)
        : camera_(camera), aspect_(aspect),
          scale_(camera.projection == Camera::Projection::Perspective ? std::tan(glm::radians(camera.fovYDegrees) * 0.5f)
                                                                      : 0.5f * camera.orthoHeight) {}

    Ray throughNdc(glm::vec2 ndc) const {
        if (camera_.projection == Camera::Projection::Perspective) {
            const glm::vec3 dirCam(ndc.x * scale_ * aspect_, -ndc.y * scale_, -1.0f);
            return {camera_.position, glm::normalize(camera_.orientation * dirCam)};
        }
        const glm::vec3 offset(ndc.x * scale_ * aspect_, -ndc.y * scale_, 0.0f);
        return {camera_.position + camera_.orientation * offset, camera_.forward()};
    }

private:
    const Camera& camera_;
    float aspect_;
    float scale_;  // tan(fov_y / 2), or half the orthographic height
};

// NDC of a pixel centre, matching the rasteriser's sample positions.
inline glm::vec2 pixelCenterNdc(int px, int py, int width, int height) {
    return {(static_cast<float>(px) + 0.5f) / static_cast<float>(width) * 2.0f - 1.0f,
            (static_cast<float>(py) + 0.5f) / static_cast<float>(height) * 2.0f - 1.0f};
}

}  // namespace hybridlab
