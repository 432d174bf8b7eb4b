// Cameras (camera.h): view matrix, reverse-Z Vulkan projections, rays through pixels, and the
// round trip between them.
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/scene/camera.h"
#include "common/scene/transform.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

glm::vec3 transformPoint(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

// Normalised device coordinates (x, y, depth) of a world point.
glm::vec3 project(const Camera& cam, float aspect, glm::vec3 world) {
    glm::vec4 clip = cam.projectionMatrix(aspect) * cam.view() * glm::vec4(world, 1.0f);
    return glm::vec3(clip) / clip.w;
}

Camera lookingCamera(Camera::Projection projection) {
    Camera cam;
    cam.projection = projection;
    cam.position = {2.0f, 3.0f, 7.0f};
    cam.orientation = Camera::lookAtOrientation(cam.position, {-1.0f, 0.5f, 0.0f});
    cam.fovYDegrees = 50.0f;
    cam.orthoHeight = 6.0f;
    cam.nearPlane = 0.1f;
    cam.farPlane = 100.0f;
    return cam;
}

TEST(Camera, OrientationAndView) {
    Camera cam;
    EXPECT_VEC_NEAR(cam.forward(), glm::vec3(0, 0, -1), 0.0f);
    EXPECT_VEC_NEAR(cam.up(), glm::vec3(0, 1, 0), 0.0f);
    EXPECT_VEC_NEAR(cam.right(), glm::vec3(1, 0, 0), 0.0f);

    // lookAtOrientation gives an orthonormal, upright, right-handed basis.
    Camera looking = lookingCamera(Camera::Projection::Perspective);
    const glm::vec3 f = glm::normalize(glm::vec3(-1.0f, 0.5f, 0.0f) - looking.position);
    EXPECT_VEC_NEAR(looking.forward(), f, 1e-6f);
    EXPECT_NEAR(glm::dot(looking.right(), glm::vec3(0, 1, 0)), 0.0f, 1e-6f) << "no roll: right is horizontal";
    EXPECT_GT(looking.up().y, 0.0f);
    EXPECT_VEC_NEAR(glm::cross(looking.right(), looking.up()), -looking.forward(), 1e-6f) << "right-handed";
    // Looking straight down the up vector falls back to another up vector instead of NaN.
    Camera down;
    down.orientation = Camera::lookAtOrientation({0, 10, 0}, {0, 0, 0});
    EXPECT_VEC_NEAR(down.forward(), glm::vec3(0, -1, 0), 1e-6f);
    EXPECT_NEAR(glm::length(down.up()), 1.0f, 1e-6f);

    // view() maps the camera position to the origin and the look-at target onto the -Z axis.
    const glm::vec3 target(-1.0f, 0.5f, 0.0f);
    const glm::mat4 v = looking.view();
    EXPECT_VEC_NEAR(transformPoint(v, looking.position), glm::vec3(0.0f), 1e-5f);
    const float distance = glm::length(target - looking.position);
    EXPECT_VEC_NEAR(transformPoint(v, target), glm::vec3(0, 0, -distance), 1e-5f);
    EXPECT_VEC_NEAR(transformPoint(v, looking.position + looking.up()), glm::vec3(0, 1, 0), 1e-5f);
    EXPECT_VEC_NEAR(transformPoint(v, looking.position + looking.right()), glm::vec3(1, 0, 0), 1e-5f);
}

TEST(Camera, ProjectionIsReverseZVulkan) {
    for (auto projection : {Camera::Projection::Perspective, Camera::Projection::Orthographic}) {
        SCOPED_TRACE(projection == Camera::Projection::Perspective ? "perspective" : "orthographic");
        Camera cam = lookingCamera(projection);
        const float aspect = 16.0f / 9.0f;
        auto onAxis = [&](float d) { return project(cam, aspect, cam.position + d * cam.forward()); };
        EXPECT_NEAR(onAxis(cam.nearPlane).z, 1.0f, 1e-5f) << "near plane at depth 1";
        EXPECT_NEAR(onAxis(cam.farPlane).z, 0.0f, 1e-5f) << "far plane at depth 0";
        EXPECT_VEC_NEAR(glm::vec2(onAxis(5.0f)), glm::vec2(0.0f), 1e-5f) << "the axis is the image centre";
        float previous = 2.0f;
        for (float d : {0.1f, 0.2f, 0.5f, 1.0f, 3.0f, 10.0f, 30.0f, 99.0f, 100.0f}) {
            float depth = onAxis(d).z;
            EXPECT_LT(depth, previous) << "depth decreases with distance (d = " << d << ")";
            EXPECT_GE(depth, -1e-6f);
            EXPECT_LE(depth, 1.0f + 1e-6f);
            previous = depth;
        }
        // Vulkan: y points down the image. Above the centre is y < 0; right of it is x > 0.
        const glm::vec3 centre = cam.position + 5.0f * cam.forward();
        glm::vec3 above = project(cam, aspect, centre + 0.5f * cam.up());
        glm::vec3 right = project(cam, aspect, centre + 0.5f * cam.right());
        EXPECT_LT(above.y, 0.0f);
        EXPECT_NEAR(above.x, 0.0f, 1e-5f);
        EXPECT_GT(right.x, 0.0f);
        EXPECT_NEAR(right.y, 0.0f, 1e-5f);
    }

    // The field of view (perspective) or height (orthographic) spans the image height.
    Camera origin;  // at the origin looking down -Z
    origin.fovYDegrees = 90.0f;
    const float aspect = 2.0f;
    // At distance d, the top edge is d * tan(45 deg) = d above the axis; the right edge is d * aspect.
    EXPECT_VEC_NEAR(glm::vec2(project(origin, aspect, {0, 3, -3})), glm::vec2(0, -1), 1e-5f);
    EXPECT_VEC_NEAR(glm::vec2(project(origin, aspect, {6, 0, -3})), glm::vec2(1, 0), 1e-5f);
    origin.projection = Camera::Projection::Orthographic;
    origin.orthoHeight = 4.0f;
    EXPECT_VEC_NEAR(glm::vec2(project(origin, aspect, {0, 2, -50})), glm::vec2(0, -1), 1e-5f);
    EXPECT_VEC_NEAR(glm::vec2(project(origin, aspect, {-4, -2, -7})), glm::vec2(-1, 1), 1e-5f);
}

TEST(Camera, PixelCenters) {
    EXPECT_VEC_NEAR(pixelCenterNdc(0, 0, 4, 2), glm::vec2(-0.75f, -0.5f), 1e-7f);
    EXPECT_VEC_NEAR(pixelCenterNdc(3, 1, 4, 2), glm::vec2(0.75f, 0.5f), 1e-7f);
    EXPECT_VEC_NEAR(pixelCenterNdc(0, 0, 1920, 1080), glm::vec2(1.0f / 1920 - 1, 1.0f / 1080 - 1), 1e-6f);
    EXPECT_VEC_NEAR(pixelCenterNdc(1919, 1079, 1920, 1080), glm::vec2(1 - 1.0f / 1920, 1 - 1.0f / 1080), 1e-6f);
    EXPECT_VEC_NEAR(pixelCenterNdc(1, 1, 3, 3), glm::vec2(0.0f), 1e-7f);

    // The top-left pixel looks up and to the left.
    Camera cam = lookingCamera(Camera::Projection::Perspective);
    Ray r = cam.rayThroughNdc(pixelCenterNdc(0, 0, 64, 48), 64.0f / 48.0f);
    EXPECT_GT(glm::dot(r.direction, cam.up()), 0.0f);
    EXPECT_LT(glm::dot(r.direction, cam.right()), 0.0f);
    EXPECT_NEAR(glm::length(r.direction), 1.0f, 1e-6f);
    EXPECT_VEC_NEAR(r.origin, cam.position, 0.0f);
}

// For pixels all over the image, a point along the pixel's ray projects back to the pixel centre.
void expectRoundTrip(const Camera& cam, int width, int height) {
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    const std::vector<glm::ivec2> pixels = {{0, 0}, {width - 1, 0}, {0, height - 1}, {width - 1, height - 1},
                                            {width / 2, height / 2}, {width / 3, 2 * height / 3}, {7, height - 5}};
    for (const auto& px : pixels) {
        const glm::vec2 ndc = pixelCenterNdc(px.x, px.y, width, height);
        const Ray ray = cam.rayThroughNdc(ndc, aspect);
        EXPECT_NEAR(glm::length(ray.direction), 1.0f, 1e-5f);
        for (float t : {0.5f, 2.0f, 13.0f, 60.0f}) {
            glm::vec3 p = project(cam, aspect, ray.origin + t * ray.direction);
            EXPECT_VEC_NEAR(glm::vec2(p), ndc, 1e-4f) << "pixel (" << px.x << ", " << px.y << "), t = " << t;
            EXPECT_GT(p.z, 0.0f);
            EXPECT_LT(p.z, 1.0f);
        }
    }
}

TEST(Camera, PerspectiveRayRoundTrip) {
    Camera cam = lookingCamera(Camera::Projection::Perspective);
    expectRoundTrip(cam, 64, 48);
    expectRoundTrip(cam, 1920, 1080);
    cam.fovYDegrees = 20.0f;
    cam.orientation = eulerDegreesToQuat({-15, 200, 10});  // with some roll
    expectRoundTrip(cam, 100, 300);
}

TEST(Camera, OrthographicRayRoundTripAndParallelRays) {
    Camera cam = lookingCamera(Camera::Projection::Orthographic);
    expectRoundTrip(cam, 64, 48);
    cam.orientation = eulerDegreesToQuat({-15, 200, 10});
    expectRoundTrip(cam, 100, 300);
    // Every ray runs along forward(); origins spread over the view rectangle in the camera plane.
    const float aspect = 2.0f;
    Ray a = cam.rayThroughNdc({-1, -1}, aspect), b = cam.rayThroughNdc({1, 1}, aspect);
    EXPECT_VEC_NEAR(a.direction, cam.forward(), 1e-6f);
    EXPECT_VEC_NEAR(b.direction, cam.forward(), 1e-6f);
    EXPECT_NEAR(glm::dot(a.origin - cam.position, cam.forward()), 0.0f, 1e-5f);
    const float h = 0.5f * cam.orthoHeight;
    EXPECT_VEC_NEAR(a.origin, cam.position - h * aspect * cam.right() + h * cam.up(), 1e-5f) << "ndc (-1, -1) is top left";
    EXPECT_VEC_NEAR(b.origin, cam.position + h * aspect * cam.right() - h * cam.up(), 1e-5f);
}

}  // namespace
}  // namespace hybridlab
