// Object placement (transform.h): Euler angle order, T * R * S, normal matrix, bounding boxes.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "common/scene/transform.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

glm::vec3 rotate(glm::vec3 degrees, glm::vec3 v) { return eulerDegreesToQuat(degrees) * v; }

glm::mat3 axisRotation(float degrees, glm::vec3 axis) {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), axis));
}

TEST(EulerAngles, RightHandedAndAppliedXThenYThenZ) {
    EXPECT_VEC_NEAR(rotate({90, 0, 0}, {0, 1, 0}), glm::vec3(0, 0, 1), 1e-6f);   // X: +Y to +Z
    EXPECT_VEC_NEAR(rotate({0, 90, 0}, {0, 0, 1}), glm::vec3(1, 0, 0), 1e-6f);   // Y: +Z to +X
    EXPECT_VEC_NEAR(rotate({0, 0, 90}, {1, 0, 0}), glm::vec3(0, 1, 0), 1e-6f);   // Z: +X to +Y
    EXPECT_VEC_NEAR(rotate({-90, 0, 0}, {0, 1, 0}), glm::vec3(0, 0, -1), 1e-6f);
    EXPECT_VEC_NEAR(rotate({0, 0, 0}, {0.3f, -0.2f, 0.9f}), glm::vec3(0.3f, -0.2f, 0.9f), 1e-7f);

    // (90, 90, 0): X first takes +Y to +Z, then Y takes +Z to +X. The other order (Y first)
    // would leave +Y where it is and then take it to +Z.
    EXPECT_VEC_NEAR(rotate({90, 90, 0}, {0, 1, 0}), glm::vec3(1, 0, 0), 1e-6f);
    // (0, 90, 90): +Z goes to +X (Y), then to +Y (Z).
    EXPECT_VEC_NEAR(rotate({0, 90, 90}, {0, 0, 1}), glm::vec3(0, 1, 0), 1e-6f);
    // (90, 0, 90): +Y goes to +Z (X), which Z leaves alone.
    EXPECT_VEC_NEAR(rotate({90, 0, 90}, {0, 1, 0}), glm::vec3(0, 0, 1), 1e-6f);

    // Equal to the explicit product Rz * Ry * Rx.
    const glm::vec3 angles[] = {{90, 90, 0}, {30, 45, 60}, {-20, 170, 5}, {10, -80, 200}};
    const glm::vec3 vectors[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.3f, -0.5f, 0.8f}};
    for (const auto& a : angles) {
        glm::mat3 R = axisRotation(a.z, {0, 0, 1}) * axisRotation(a.y, {0, 1, 0}) * axisRotation(a.x, {1, 0, 0});
        for (const auto& v : vectors) EXPECT_VEC_NEAR(rotate(a, v), R * v, 1e-5f);
    }
}

TEST(TransformMatrix, ScaleThenRotateThenTranslate) {
    Transform t;
    t.position = {10, 20, 30};
    t.rotation = eulerDegreesToQuat({0, 90, 0});
    t.scale = {2, 3, 4};
    const glm::vec3 p(1, 1, 1);
    // S: (2, 3, 4); R (90 about Y: x -> -z, z -> x): (4, 3, -2); T: (14, 23, 28).
    EXPECT_VEC_NEAR(glm::vec3(t.matrix() * glm::vec4(p, 1.0f)), glm::vec3(14, 23, 28), 1e-5f);
    const glm::vec3 q(0.5f, -1.0f, 2.0f);
    EXPECT_VEC_NEAR(glm::vec3(t.matrix() * glm::vec4(q, 1.0f)), t.position + t.rotation * (t.scale * q), 1e-5f);
    // Directions ignore the translation.
    EXPECT_VEC_NEAR(glm::vec3(t.matrix() * glm::vec4(1, 0, 0, 0)), glm::vec3(0, 0, -2), 1e-5f);

    // The default transform is the identity.
    const glm::mat4 m = Transform{}.matrix();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_EQ(m[c][r], c == r ? 1.0f : 0.0f);
}

TEST(NormalMatrix, KeepsNormalsPerpendicular) {
    // A plane through the origin with normal n, containing the tangents a and b.
    const glm::vec3 n = glm::normalize(glm::vec3(1, 1, 0));
    const glm::vec3 a = glm::normalize(glm::vec3(1, -1, 0)), b(0, 0, 1);
    Transform t;
    t.rotation = eulerDegreesToQuat({20, 40, 60});
    t.scale = {1, 4, 0.5f};
    t.position = {3, -2, 1};
    const glm::mat4 M = t.matrix();
    const glm::vec3 nT = normalMatrix(M) * n;
    const glm::vec3 aT = glm::mat3(M) * a, bT = glm::mat3(M) * b;
    EXPECT_NEAR(glm::dot(glm::normalize(nT), glm::normalize(aT)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(glm::normalize(nT), glm::normalize(bT)), 0.0f, 1e-6f);
    // The check has teeth: transforming the normal like a position tilts it.
    EXPECT_GT(std::abs(glm::dot(glm::normalize(glm::mat3(M) * n), glm::normalize(aT))), 0.1f);

    // For rigid transforms it is the rotation.
    Transform rigid;
    rigid.rotation = eulerDegreesToQuat({10, 20, 30});
    rigid.position = {5, 5, 5};
    const glm::mat3 N = normalMatrix(rigid.matrix()), R = glm::mat3_cast(rigid.rotation);
    for (int c = 0; c < 3; ++c) EXPECT_VEC_NEAR(N[c], R[c], 1e-6f);
}

TEST(Aabb, ExtendAndTransform) {
    Aabb b;
    EXPECT_FALSE(b.valid());
    b.extend(glm::vec3(1, 2, 3));
    EXPECT_TRUE(b.valid());
    EXPECT_VEC_NEAR(b.extent(), glm::vec3(0.0f), 0.0f);
    Aabb other;
    b.extend(other);  // an empty box adds nothing
    EXPECT_VEC_NEAR(b.lo, glm::vec3(1, 2, 3), 0.0f);
    EXPECT_VEC_NEAR(b.hi, glm::vec3(1, 2, 3), 0.0f);
    EXPECT_FALSE(Aabb{}.transformed(glm::mat4(1.0f)).valid());

    // transformed() bounds the eight transformed corners.
    Aabb unit{glm::vec3(-0.5f), glm::vec3(0.5f)};
    Transform t;
    t.position = {1, 2, 3};
    t.rotation = eulerDegreesToQuat({0, 45, 0});
    t.scale = {2, 1, 2};
    Aabb turned = unit.transformed(t.matrix());
    // A 2 x 1 x 2 box turned 45 degrees about Y: sqrt(8) wide in x and z.
    const float h = std::sqrt(2.0f);
    EXPECT_VEC_NEAR(turned.lo, glm::vec3(1 - h, 1.5f, 3 - h), 1e-5f);
    EXPECT_VEC_NEAR(turned.hi, glm::vec3(1 + h, 2.5f, 3 + h), 1e-5f);
    EXPECT_VEC_NEAR(turned.center(), glm::vec3(1, 2, 3), 1e-5f);

    Aabb offCentre{glm::vec3(0, 0, 0), glm::vec3(1, 2, 3)};
    Aabb mirrored = offCentre.transformed(glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1)));
    EXPECT_VEC_NEAR(mirrored.lo, glm::vec3(-1, 0, 0), 0.0f);
    EXPECT_VEC_NEAR(mirrored.hi, glm::vec3(0, 2, 3), 0.0f);
}

}  // namespace
}  // namespace hybridlab
