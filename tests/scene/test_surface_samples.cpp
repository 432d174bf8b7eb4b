// Area-uniform points over objects' surfaces (surface_samples.h): on the surfaces, in proportion
// to each one's area, uniform within a triangle, the same for a seed.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "common/scene/primitives.h"
#include "common/scene/scene.h"
#include "common/scene/surface_samples.h"

namespace hybridlab {
namespace {

// Two unit-square planes: one at y = 0, one stretched to area 2 at y = 5.
Scene twoPlanes() {
    Scene scene;
    scene.meshes.push_back(makePlane());
    SceneObject small, large;
    small.name = "small";
    small.meshes = {0};
    large.name = "large";
    large.meshes = {0};
    large.transform.position = {0.0f, 5.0f, 0.0f};
    large.transform.scale = {2.0f, 1.0f, 1.0f};
    scene.objects = {small, large};
    return scene;
}

TEST(SurfaceSamples, AreaUniformOverTheObjects) {
    const Scene scene = twoPlanes();
    constexpr std::size_t kCount = 6000;
    const std::vector<glm::vec3> points = sampleObjectSurfaces(scene, {0, 1}, kCount, 11);
    ASSERT_EQ(points.size(), kCount);
    int onLarge = 0, offSurface = 0, largeInnerHalf = 0, smallLeftHalf = 0;
    for (const glm::vec3& p : points) {
        const bool large = p.y > 2.5f;
        if (large) {
            ++onLarge;
            if (std::abs(p.x) < 0.5f) ++largeInnerHalf;
        } else if (p.x < 0.0f) {
            ++smallLeftHalf;
        }
        const float halfWidth = large ? 1.0f : 0.5f;
        if (std::abs(p.y - (large ? 5.0f : 0.0f)) > 1e-5f || std::abs(p.x) > halfWidth + 1e-5f || std::abs(p.z) > 0.5f + 1e-5f) ++offSurface;
    }
    EXPECT_EQ(offSurface, 0);
    // Binomial standard deviations: sqrt(n p (1 - p)) is about 37 of 6000 and 32 of 4000.
    EXPECT_NEAR(onLarge, 4000, 120) << "two thirds of the area";
    EXPECT_NEAR(largeInnerHalf, onLarge / 2, 100) << "uniform within the stretched plane";
    EXPECT_NEAR(smallLeftHalf, (static_cast<int>(kCount) - onLarge) / 2, 100) << "uniform across its two triangles";

    EXPECT_EQ(sampleObjectSurfaces(scene, {0, 1}, 50, 11), sampleObjectSurfaces(scene, {0, 1}, 50, 11)) << "same seed, same points";
    EXPECT_NE(sampleObjectSurfaces(scene, {0, 1}, 50, 11), sampleObjectSurfaces(scene, {0, 1}, 50, 12));
    for (const glm::vec3& p : sampleObjectSurfaces(scene, {1}, 200, 3)) EXPECT_NEAR(p.y, 5.0f, 1e-5f) << "only the objects asked for";
    EXPECT_TRUE(sampleObjectSurfaces(scene, {}, 10, 1).empty());
}

}  // namespace
}  // namespace hybridlab
