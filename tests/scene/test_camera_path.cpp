// Keyframes (keyframes.h), camera paths (camera_path.h) and rigid animation (rigid_animation.h):
// keys are hit exactly, Catmull-Rom is smooth with uneven key times, times clamp, frames count.
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/scene/camera_path.h"
#include "common/scene/keyframes.h"
#include "common/scene/rigid_animation.h"
#include "common/scene/transform.h"
#include "tests/support/test_support.h"

namespace hybridlab {
namespace {

// Uneven key times on purpose: uniform Catmull-Rom formulas would not pass these tests.
CameraPath lookAtPath(Interpolation mode) {
    CameraPath p;
    p.interpolation = mode;
    p.times = {0.0, 0.5, 2.0, 2.25, 4.0};
    p.positions = {{0, 1, 10}, {4, 2, 8}, {8, 1, 0}, {7, 3, -3}, {-5, 2, -6}};
    p.targets = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 2}, {0, 0, 0}};
    return p;
}

TEST(KeySegment, FindsTheSegmentAndClamps) {
    const std::vector<double> times = {1.0, 2.0, 4.0};
    auto s = findSegment(times, 1.5);
    EXPECT_EQ(s.index, 0u);
    EXPECT_FLOAT_EQ(s.u, 0.5f);
    s = findSegment(times, 3.0);
    EXPECT_EQ(s.index, 1u);
    EXPECT_FLOAT_EQ(s.u, 0.5f);
    s = findSegment(times, 2.0);  // a key starts its segment
    EXPECT_EQ(s.index, 1u);
    EXPECT_FLOAT_EQ(s.u, 0.0f);
    s = findSegment(times, -5.0);
    EXPECT_EQ(s.index, 0u);
    EXPECT_FLOAT_EQ(s.u, 0.0f);
    s = findSegment(times, 9.0);
    EXPECT_EQ(s.index, 1u);
    EXPECT_FLOAT_EQ(s.u, 1.0f);
}

TEST(Keyframes, BothModesHitEveryKeyAreContinuousAndClamp) {
    for (auto mode : {Interpolation::Linear, Interpolation::CatmullRom}) {
        SCOPED_TRACE(mode == Interpolation::Linear ? "linear" : "catmull-rom");
        const CameraPath p = lookAtPath(mode);
        Camera lens;
        lens.fovYDegrees = 33.0f;
        // At every key time: the key's position, looking at the key's target.
        for (std::size_t k = 0; k < p.times.size(); ++k) {
            Camera c = p.evaluate(p.times[k], lens);
            EXPECT_VEC_NEAR(c.position, p.positions[k], 1e-5f) << "key " << k;
            EXPECT_VEC_NEAR(c.forward(), glm::normalize(p.targets[k] - p.positions[k]), 1e-5f) << "key " << k;
            EXPECT_EQ(c.fovYDegrees, 33.0f) << "the lens is kept";
        }
        // Just before and just after an inner key agree.
        const double eps = 1e-6;
        for (std::size_t k = 1; k + 1 < p.times.size(); ++k) {
            glm::vec3 before = interpolate(p.times, p.positions, p.times[k] - eps, mode);
            glm::vec3 after = interpolate(p.times, p.positions, p.times[k] + eps, mode);
            EXPECT_VEC_NEAR(before, after, 1e-3f) << "key " << k;
            EXPECT_VEC_NEAR(before, p.positions[k], 1e-3f) << "key " << k;
        }
        // Outside the keys: the first or last key.
        EXPECT_VEC_NEAR(p.evaluate(-3.0, lens).position, p.positions.front(), 1e-6f);
        EXPECT_VEC_NEAR(p.evaluate(100.0, lens).position, p.positions.back(), 1e-6f);
        EXPECT_VEC_NEAR(p.evaluate(100.0, lens).forward(), glm::normalize(p.targets.back() - p.positions.back()), 1e-5f);
        // A single key is a constant.
        const std::vector<double> oneTime = {1.0};
        const std::vector<glm::vec3> oneValue = {{1, 2, 3}};
        EXPECT_VEC_NEAR(interpolate(oneTime, oneValue, 0.0, mode), glm::vec3(1, 2, 3), 0.0f);
        EXPECT_VEC_NEAR(interpolate(oneTime, oneValue, 5.0, mode), glm::vec3(1, 2, 3), 0.0f);
    }
}

TEST(Keyframes, LinearMidpointIsTheAverage) {
    const CameraPath p = lookAtPath(Interpolation::Linear);
    for (std::size_t k = 0; k + 1 < p.times.size(); ++k) {
        double mid = 0.5 * (p.times[k] + p.times[k + 1]);
        EXPECT_VEC_NEAR(interpolate(p.times, p.positions, mid, Interpolation::Linear), 0.5f * (p.positions[k] + p.positions[k + 1]), 1e-5f);
    }
    // A quarter of the way through the segment from 0.5 to 2.0.
    EXPECT_VEC_NEAR(interpolate(p.times, p.positions, 0.875, Interpolation::Linear), glm::vec3(5, 1.75f, 6), 1e-5f);
}

TEST(Keyframes, CatmullRomHasContinuousVelocityWithUnevenKeyTimes) {
    // The non-uniform tangents m_i = (p_(i+1) - p_(i-1)) / (t_(i+1) - t_(i-1)) make the velocity
    // continuous at keys even where neighbouring segments differ in length (0.5 s vs 1.5 s vs 0.25 s).
    const CameraPath p = lookAtPath(Interpolation::CatmullRom);
    const double h = 1e-4;
    auto velocity = [&](double t0, double t1) {
        return (interpolate(p.times, p.positions, t1, Interpolation::CatmullRom) -
                interpolate(p.times, p.positions, t0, Interpolation::CatmullRom)) / static_cast<float>(t1 - t0);
    };
    for (std::size_t k = 1; k + 1 < p.times.size(); ++k) {
        const double t = p.times[k];
        glm::vec3 left = velocity(t - h, t), right = velocity(t, t + h);
        glm::vec3 expected = (p.positions[k + 1] - p.positions[k - 1]) / static_cast<float>(p.times[k + 1] - p.times[k - 1]);
        EXPECT_VEC_NEAR(left, expected, 0.02f * glm::length(expected) + 0.01f) << "key " << k;
        EXPECT_VEC_NEAR(right, expected, 0.02f * glm::length(expected) + 0.01f) << "key " << k;
    }

    // Keys on a straight line at uneven times, with positions proportional to time: a cubic
    // Hermite with these tangents reproduces the line exactly.
    const std::vector<double> times = {0.0, 0.3, 1.0, 3.0};
    std::vector<glm::vec3> values;
    for (double t : times) values.push_back(glm::vec3(2, -1, 0.5f) * static_cast<float>(t));
    for (double t = 0.0; t <= 3.0; t += 0.1) {
        EXPECT_VEC_NEAR(interpolate(times, values, t, Interpolation::CatmullRom), glm::vec3(2, -1, 0.5f) * static_cast<float>(t), 1e-5f)
            << "t = " << t;
    }
}

TEST(Keyframes, OrientationsSlerpOnTheShortestArc) {
    const std::vector<double> times = {0.0, 2.0};
    const std::vector<glm::quat> q = {eulerDegreesToQuat({0, 0, 0}), eulerDegreesToQuat({0, 90, 0})};
    glm::quat mid = interpolate(times, q, 1.0);
    glm::vec3 f = mid * glm::vec3(0, 0, -1);
    // Halfway between yaw 0 and yaw 90 is yaw 45.
    EXPECT_VEC_NEAR(f, eulerDegreesToQuat({0, 45, 0}) * glm::vec3(0, 0, -1), 1e-5f);
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(f, glm::vec3(0, 0, -1)))), 45.0f, 1e-3f);
    // The same rotation written as -q must not send the interpolation the long way round.
    const std::vector<glm::quat> flipped = {q[0], -q[1]};
    EXPECT_VEC_NEAR(interpolate(times, flipped, 1.0) * glm::vec3(0, 0, -1), f, 1e-5f);
    EXPECT_VEC_NEAR(interpolate(times, q, 0.5) * glm::vec3(0, 0, -1), eulerDegreesToQuat({0, 22.5f, 0}) * glm::vec3(0, 0, -1), 1e-5f);
}

TEST(CameraPath, OrientationKeyedPathSlerps) {
    CameraPath p;
    p.keysLookAt = false;
    p.interpolation = Interpolation::CatmullRom;
    p.times = {0.0, 1.0};
    p.positions = {{0, 0, 0}, {0, 0, 0}};
    p.orientations = {eulerDegreesToQuat({0, 0, 0}), eulerDegreesToQuat({0, 90, 0})};
    Camera lens;
    Camera c = p.evaluate(0.5, lens);
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(c.forward(), glm::vec3(0, 0, -1)))), 45.0f, 1e-3f);
    EXPECT_VEC_NEAR(c.forward(), glm::normalize(glm::vec3(-1, 0, -1)), 1e-5f);
    EXPECT_VEC_NEAR(p.evaluate(0.0, lens).forward(), glm::vec3(0, 0, -1), 1e-6f);
    EXPECT_VEC_NEAR(p.evaluate(1.0, lens).forward(), glm::vec3(-1, 0, 0), 1e-6f);
}

TEST(CameraPath, FrameCountAndTimes) {
    CameraPath p;
    p.times = {0.0, 1.0, 2.0};
    p.framesPerSecond = 30.0;
    EXPECT_EQ(p.frameCount(), 61);  // frames at 0, 1/30, ..., 60/30 = 2 s
    EXPECT_DOUBLE_EQ(p.frameTime(0), 0.0);
    EXPECT_DOUBLE_EQ(p.frameTime(60), 2.0);
    EXPECT_DOUBLE_EQ(p.duration(), 2.0);

    p.times = {1.0, 21.0};  // 20 s starting at 1 s
    EXPECT_EQ(p.frameCount(), 601);
    EXPECT_DOUBLE_EQ(p.startTime(), 1.0);
    EXPECT_DOUBLE_EQ(p.frameTime(0), 1.0);
    EXPECT_NEAR(p.frameTime(600), 21.0, 1e-9);

    p.times = {0.0, 0.1};  // 0.1 s at 30 fps: frames at 0, 1/30, 2/30, 3/30 (3.0000000000000004 frames)
    EXPECT_EQ(p.frameCount(), 4);
    p.times = {0.0, 1.01};  // the last frame (at 1.0 s) does not reach the last key
    EXPECT_EQ(p.frameCount(), 31);
    p.framesPerSecond = 24.0;
    p.times = {0.0, 0.5};
    EXPECT_EQ(p.frameCount(), 13);
    EXPECT_DOUBLE_EQ(p.frameTime(12), 0.5);
}

TEST(RigidAnimation, KeysAreHitAndSegmentsInterpolate) {
    RigidAnimation a;
    a.times = {0.0, 1.0, 3.0};
    a.positions = {{0, 0, 0}, {2, 0, 0}, {2, 4, 0}};
    a.rotations = {eulerDegreesToQuat({0, 0, 0}), eulerDegreesToQuat({0, 90, 0}), eulerDegreesToQuat({0, 90, 90})};
    a.scales = {glm::vec3(1), glm::vec3(2), glm::vec3(1, 3, 1)};
    ASSERT_FALSE(a.empty());
    for (auto mode : {Interpolation::Linear, Interpolation::CatmullRom}) {
        a.interpolation = mode;
        for (std::size_t k = 0; k < a.times.size(); ++k) {
            Transform t = a.at(a.times[k]);
            EXPECT_VEC_NEAR(t.position, a.positions[k], 1e-5f);
            EXPECT_VEC_NEAR(t.scale, a.scales[k], 1e-5f);
            EXPECT_VEC_NEAR(t.rotation * glm::vec3(1, 2, 3), a.rotations[k] * glm::vec3(1, 2, 3), 1e-5f);
        }
        EXPECT_VEC_NEAR(a.at(-1.0).position, a.positions.front(), 1e-6f);
        EXPECT_VEC_NEAR(a.at(10.0).position, a.positions.back(), 1e-6f);
    }
    a.interpolation = Interpolation::Linear;
    Transform mid = a.at(0.5);
    EXPECT_VEC_NEAR(mid.position, glm::vec3(1, 0, 0), 1e-6f);
    EXPECT_VEC_NEAR(mid.scale, glm::vec3(1.5f), 1e-6f);
    EXPECT_VEC_NEAR(mid.rotation * glm::vec3(0, 0, 1), eulerDegreesToQuat({0, 45, 0}) * glm::vec3(0, 0, 1), 1e-5f);
    EXPECT_VEC_NEAR(a.at(2.0).position, glm::vec3(2, 2, 0), 1e-6f);
    EXPECT_TRUE(RigidAnimation{}.empty());
}

}  // namespace
}  // namespace hybridlab
