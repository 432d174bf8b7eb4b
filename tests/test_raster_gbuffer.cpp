// The G-buffer against the reference's primary rays (DESIGN.md "Invariants that tests hold"): at
// every pixel centre the rasterised object id, world position and shading normal agree with the
// Whitted reference's camera-ray hit, except for a thin band of silhouette pixels. And the two ways
// of counting visible pixels per object (Walewski 2019 §3.2's A) agree.
#include <cmath>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "common/raster/rasterizer.h"
#include "common/raytrace/ray_scene.h"
#include "common/scene/scene_catalog.h"
#include "common/scene/scene_file.h"
#include "tests/raster_test_support.h"
#include "tests/test_support.h"

namespace hybridlab {
namespace {

constexpr int kWidth = 640, kHeight = 360;

struct Agreement {
    std::size_t covered = 0, idMatches = 0, facingMatches = 0;
    double maxPositionError = 0.0;  // over pixels whose ids match, relative to the bounding-box diagonal
    double maxNormalDegrees = 0.0;
    double idAgreement() const { return covered ? static_cast<double>(idMatches) / covered : 1.0; }
};

Agreement compareWithPrimaryRays(const Scene& scene, const GBuffer& g) {
    RayScene rays(scene);
    const Camera& camera = scene.camera;
    const float aspect = static_cast<float>(g.width) / static_cast<float>(g.height);
    const double diagonal = glm::length(scene.bounds().extent());
    Agreement a;
    for (int y = 0; y < g.height; ++y) {
        for (int x = 0; x < g.width; ++x) {
            const std::size_t i = g.index(x, y);
            const Ray ray = camera.rayThroughNdc(pixelCenterNdc(x, y, g.width, g.height), aspect);
            SurfaceHit hit;
            const bool hits = rays.intersect(ray, 0.0f, std::numeric_limits<float>::infinity(), hit);
            const std::uint32_t reference = hits ? hit.object + 1 : kSkyObjectId;
            if (reference == kSkyObjectId && g.objectId[i] == kSkyObjectId) continue;
            ++a.covered;
            if (reference != g.objectId[i]) continue;
            ++a.idMatches;
            a.maxPositionError = std::max(a.maxPositionError, glm::length(glm::vec3(g.position[i]) - hit.position) / diagonal);
            const float c = std::clamp(glm::dot(glm::normalize(glm::vec3(g.normal[i])), hit.shadingNormal), -1.0f, 1.0f);
            a.maxNormalDegrees = std::max(a.maxNormalDegrees, static_cast<double>(glm::degrees(std::acos(c))));
            const bool front = glm::dot(ray.direction, hit.geometricNormal) < 0.0f;
            a.facingMatches += front == g.frontFace(i);
        }
    }
    return a;
}

class GBufferAgreesWithPrimaryRays : public ::testing::TestWithParam<const char*> {};

TEST_P(GBufferAgreesWithPrimaryRays, OnTheScene) {
    const std::string name = GetParam();
    if (name.rfind("sponza", 0) == 0 && !test::assetsFromEnvironment()) GTEST_SKIP() << "HYBRIDLAB_ASSETS is not set";
    const Scene scene = loadSceneFile(findSceneFile(name));
    RASTERIZER_OR_SKIP(raster, scene);
    RasterRequest request;
    request.camera = scene.camera;
    request.width = kWidth;
    request.height = kHeight;
    request.readback = kGBufferPosition | kGBufferNormal | kGBufferObjectId;
    request.lighting = false;
    const RasterFrame frame = raster->render(request);
    const Agreement a = compareWithPrimaryRays(scene, frame.gbuffer);
    std::printf("[ raster   ] %s: %zu covered pixels, ids agree on %.4f%%, facing on %zu of %zu, max position error %.3g of the "
                "diagonal, max normal error %.4f deg\n",
                name.c_str(), a.covered, 100.0 * a.idAgreement(), a.facingMatches, a.idMatches, a.maxPositionError, a.maxNormalDegrees);
    RecordProperty("id_agreement", std::to_string(a.idAgreement()));
    EXPECT_GT(a.covered, static_cast<std::size_t>(kWidth * kHeight / 10));
    EXPECT_GE(a.idAgreement(), 0.99);
    EXPECT_LT(a.maxPositionError, 1e-3);
    EXPECT_LT(a.maxNormalDegrees, 0.5);
    EXPECT_EQ(a.facingMatches, a.idMatches);
}

INSTANTIATE_TEST_SUITE_P(Raster, GBufferAgreesWithPrimaryRays, ::testing::Values("whitted-classic", "cornell-mirror-glass", "sponza-spheres"),
                         [](const auto& info) {
                             std::string n = info.param;
                             for (char& c : n)
                                 if (c == '-') c = '_';
                             return n;
                         });

}  // namespace
}  // namespace hybridlab
