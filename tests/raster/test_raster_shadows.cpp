// Shadow maps against the reference's shadow rays, one light type at a time: a box floating over
// a floor, seen from above. Away from the shadow's edge (where PCF blurs what the ray tracer keeps
// hard), lit and shadowed pixels are the same in both, and acne does not darken the lit floor.
#include <cstdio>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "common/scene/primitives.h"
#include "techniques/technique.h"
#include "tests/support/raster_test_support.h"
#include "tests/support/scene_fixtures.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 320, kHeight = 240;

Scene boxOverFloor(Light light) {
    using namespace test;
    SceneBuilder b;
    b.object("floor", makePlane(), b.material(matte({0.8f, 0.8f, 0.8f})), placed({0, 0, 0}, {10, 1, 10}));
    b.object("box", makeCube(), b.material(matte({0.5f, 0.2f, 0.2f})), placed({0.3f, 1.2f, 0}, {1.2f, 0.4f, 1.2f}, {0, 30, 0}));
    b.light(light);
    Scene& s = b.scene();
    s.camera.position = {0, 9, 0.01f};
    s.camera.orientation = Camera::lookAtOrientation(s.camera.position, {0, 0, 0}, {0, 0, -1});
    s.camera.fovYDegrees = 50.0f;
    return s;
}

Image render(const Scene& scene, const std::string& technique, const std::vector<std::pair<std::string, ParamValue>>& params) {
    SceneContext context(scene);
    auto t = createTechnique(technique, params);
    t->prepare(context);
    return t->render(context, {scene.camera, 0.0, kWidth, kHeight}).image;
}

TEST(RasterShadows, ShadowMapsAgreeWithShadowRaysForEveryLightType) {
    Light directional;
    directional.type = Light::Type::Directional;
    directional.direction = glm::normalize(glm::vec3(0.9f, -1.0f, 0.3f));
    Light point;
    point.type = Light::Type::Point;
    point.position = {-1, 4, 1};
    point.intensity = 16.0f;
    Light spot = point;
    spot.type = Light::Type::Spot;
    spot.direction = glm::normalize(glm::vec3(0.2f, -1.0f, -0.1f));
    spot.innerConeDegrees = 35.0f;
    spot.outerConeDegrees = 50.0f;
    {
        const Scene probe = boxOverFloor(point);
        RASTERIZER_OR_SKIP(unused, probe);
    }
    for (const Light& light : {directional, point, spot}) {
        const Scene scene = boxOverFloor(light);
        const Image raster = render(scene, "raster", {{"shadows", std::string("map")}});
        const Image whitted = render(scene, "whitted", {});
        const Image unshadowed = render(scene, "whitted", {{"shadows", false}});
        std::size_t shadowed = 0, lit = 0, disagree = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const float full = unshadowed.at(x, y).g, ref = whitted.at(x, y).g, ras = raster.at(x, y).g;
                if (full < 1e-4f) continue;  // outside a spot cone
                const bool refShadowed = ref < 0.5f * full, rasShadowed = ras < 0.5f * full;
                shadowed += refShadowed;
                lit += !refShadowed;
                disagree += refShadowed != rasShadowed;
            }
        }
        const char* type = lightTypeName(light.type);
        std::printf("[ raster   ] %s light: %zu shadowed and %zu lit pixels by shadow rays; shadow maps disagree on %zu\n", type, shadowed,
                    lit, disagree);
        EXPECT_GT(shadowed, 1000u) << type;
        EXPECT_GT(lit, 1000u) << type;
        EXPECT_LE(disagree, (shadowed + lit) / 100) << type;  // the edge band
    }
}

}  // namespace
}  // namespace hybridlab
